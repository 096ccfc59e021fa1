#include "cli/help_text.hpp"
#include <algorithm>

namespace terrace::cli {

namespace {

struct Command {
    const char* name;
    const char* synopsis;    // one line or more, each starting "  terrace ..."
    const char* description; // indented paragraphs
    const char* options;     // "  --option  what it does" lines
    bool stops;              // a run: the notes on signals apply
};

const char* header =
    R"(terrace — event-driven dynamics of rigid bodies on terraced potentials (DMD)
and standard rigid-body MD on the continuous potential (SMD), compared on one scene.
)";

const char* sceneOptions =
    R"(  SCENE.json            the scene (experiments/scenes/ holds some); none: the built-in
                        dense rods, N 512, rho* 0.5, T* 1.4
  --set KEY=VALUE       set a scene key by its dotted path, e.g. --set engine=smd,
                        --set dmd.dV=0.5, --set state.temperature=2; VALUE is JSON, or a bare
                        string when it does not parse (--set smd.scheme=omelyan). An unknown key
                        is refused, naming the known key nearest it
)";

const Command commands[] = {
    {"run",
     R"(  terrace run [SCENE.json] [--set KEY=VALUE]... [--out DIR] [--overwrite] [--strict]
              [--quiet]
  terrace run --continue DIR [--quiet]
)",
     R"(      Run a scene with its engine (engine = dmd | smd). Run lengths and output intervals
      are whole multiples of their intervals, or refused with the nearest valid values.
      A step table (potential.kind steps: square wells, Chapela's LJ, DynamO's tables) runs
      under dmd only: smd refuses it, a step's force being an impulse it cannot integrate.
      Writes DIR/summary.json, scene.json, initial.xyz, rdf.csv, vacf.csv, oacf.csv, msd.csv,
      thermo.csv (about 100 rows by default; output.thermo_every_fs=0 for none) and, if asked
      for, trajectory.xyz (extended XYZ, read by OVITO and ASE) or, with
      output.trajectory_format=gsd, trajectory.gsd (HOOMD's GSD, read by OVITO, freud and gsd,
      with orientations and the bodies' shapes).
      A lattice start fills the box on state.lattice = sc (default) | fcc | bcc, the first N
      sites of the smallest lattice that holds them; state.lattice_aspect stretches sc only.
      summary.json counts collisions (collisions_per_ps, collisions_per_cpu_second) apart from
      all DMD events, cell, relist and virtual ones included (all_events_per_cpu_second).
      With output.restart_every_ps > 0 the run keeps DIR/restart.bin (the bodies and the
      analysis' and statistics' accumulators, no sample: its size does not grow with the run)
      until it ends, from which --continue goes on.
      Production is NVE unless run.heat_bath sets a heat bath, which acts from the start of
      equilibration: {"kind":"andersen","rate_per_ps":ν} (both engines) or
      {"kind":"csvr","tau_fs":τ} (Bussi's stochastic rescaling); summary.json's heat_bath
      then gives the effective energy and ⟨K⟩, Var(K) against the canonical ones.
      Units (docs/UNITS.md): real by default (Å, g/mol, kJ/mol, K, and fs or ps as a key's
      name says); with units=lj, reduced units of the scene's model (σ and ε of its potential,
      m its body mass, τ = σ·sqrt(m/ε)): the closing lines, thermo.csv, the CSVs and
      summary.json's "reduced" entry give T*, U/N in ε, times in τ, r in σ, P* and D in σ²/τ;
      unit-free keys (run.time, run.sample, output.thermo_every, smd.dt, ...) are read in τ
      or σ, keys named in a unit (run.time_ps) in that unit. state.temperature (T*) and
      state.density (ρ*) are reduced under both.
)",
     R"(  --out DIR             the output directory (default: out/<scene name>-<engine>, then the
                        --set keys but name and engine as key=value, sorted by the whole key
                        and joined by ',': out/lj-liquid-smd-dt_fs=0.7). A DIR that holds an
                        earlier run's results is refused unless --overwrite
  --overwrite           remove an earlier run's results from DIR first
  --strict              refuse a --set key that the run's engine does not read (smd.* on a DMD
                        run, dmd.* on an SMD one) instead of warning about it
  --continue DIR        continue the run in DIR from its restart file, extending its output as
                        if it had never stopped (no scene, --set, --out or --overwrite)
  --quiet               no progress output
)",
     true},
    {"analyse", R"(  terrace analyse DIR
)",
     R"(      Recompute the correlation CSVs of DIR from DIR/trajectory.xyz (or trajectory.gsd),
      read frame by frame into the accumulators a run uses, with the run's analysis
      settings (DIR/scene.json; without it the defaults, g(r) out to L/2). A last frame cut
      short by a killed run is left out, with a warning. Also spelt analyze.
)",
     "", false},
    {"compare", R"(  terrace compare A.csv B.csv [--tol-sigma X] [--column NAME]
)",
     R"(      Regression check of two correlation curves (rdf.csv, vacf.csv, msd.csv, ...): B is
      interpolated onto A's points and each difference weighed by both error bars. Prints the
      verdict; exit status 0 when they agree, 1 when they do not.
)",
     R"(  --tol-sigma X         the tolerance in standard deviations (default 3: a false alarm on
                        0.27 % of agreeing pairs), > 0
  --column NAME         the value column (default: A's first column after x)
)",
     false},
    {"design", R"(  terrace design [SCENE.json] [--set KEY=VALUE]... [--profile] [--strict]
)",
     R"(      The terraces the scene's DMD runs on (dmd.dV, dmd.levels or the design of
      dmd.terraces), as CSV: each terrace's levels and energy. It reads the dmd section only,
      whatever the scene's engine.
)",
     R"(  --profile             instead, U along the design's reference alignment (s_i.s_j =
                        1/sqrt 2; for rods r_e = r) beside its terraced value
  --strict              refuse a --set key of the smd section (design does not read it)
                        instead of warning about it
)",
     false},
    {"sweep",
     R"(  terrace sweep SWEEP.json [--out DIR] [-j N] [--set KEY=VALUE]... [--retry-failed]
                [--strict] [--quiet]
)",
     R"(      Run every scene of a sweep: a base scene and axes of values for dotted scene keys
      (product, zipped, or cases), and seeds, as in
        {"scene": "dense-rods.json", "set": {"state.n": 216},
         "axes": [{"state.density": [0.1, 0.5]},
                  {"cases": [{"engine": "dmd", "dmd.dV": 0.5},
                             {"engine": "smd", "smd.dt_fs": 1.8}]}],
         "seeds": [1, 2]}
      Each run goes to DIR/<its overrides> (e.g. density-0.1_engine-dmd_dV-0.5_seed-1), one
      row each in DIR/sweep.csv. Under mpirun every rank takes runs as they come (DIR on a
      file system all ranks see). Runs done before for the same scene are not run again, nor
      failed ones (unless --retry-failed); a failed run is recorded and the sweep goes on.
      A key of one engine's section that an axis value sets for runs of the other engine,
      with their engine or with nothing else they read, is a warning, as is a common key
      ("set", --set) of an engine no run has: keys of both engines may be set for a sweep
      that runs both. Exit status 0: all runs done; 1: some
      failed; 2: a bad sweep file; 3: the sweep itself failed (another sweep holds DIR, a
      table it cannot write); 128 + signal: stopped.
)",
     R"(  --set KEY=VALUE       set a scene key for every run, after the file's "set"
  --out DIR             the sweep's directory (default: out/<sweep file name>, then the --set
                        keys as for terrace run)
  -j N                  runs at once (default 1; 0 only under mpirun: rank 0 then only hands
                        out runs)
  --retry-failed        run again the runs whose failure is recorded
  --strict              refuse the sweep (exit status 2) where the warnings above would be
  --quiet               no progress output
)",
     true},
    {"tradeoff",
     R"(  terrace tradeoff [SCENE.json] [--tolerance OBS=VALUE[%]]... [--set KEY=VALUE]...
                   [-j N] [--out DIR] [--bias-n N] [--max-replicas N] [--cost-pairs N]
                   [--budget-cpu-hours H] [--dV LIST] [--designs uniform,optimal]
                   [--schemes verlet,omelyan,yoshida4] [--observables LIST] [--frontier]
                   [--quiet]
)",
     R"(      Does DMD pay for this scene at these tolerances? Measures each engine's systematic
      error against the continuous model (reference: SMD yoshida4 at half smd.dt_fs) on
      u = <U>/(N eps), p = P*, d = D, g = RMS of g(r), g_peak, tau_v and tau_o (the
      VACF's and OACF's integrals), over a ladder of DMD dV (uniform and optimal terraces)
      and SMD dt for verlet, omelyan and yoshida4 up to the stability limit. Each bias is
      resolved within or outside its tolerance at 2 sigma (Bonferroni over the replica
      counts looked at), replicas added where it is not (each round to each engine's
      cheapest open setting that is cheaper than its cheapest one within; --frontier: to
      every ladder's), up to --max-replicas or the budget;
      the bias law (dt^2, dt^4, dV^p) places a setting between the last within and the first
      outside, checked by its own runs. Once one engine's cheapest setting within is timed
      cheaper than any setting of the other could be (every cheaper one resolved outside on
      an observable whose bias grows with dV or dt, or, where none is, the other's coarsest
      setting short of its stability limit, none coarser being a candidate), it stops: the
      verdict then says "at least", the ratio to that bounding setting (--frontier resolves
      both engines instead). DMD's u, p, g and g_peak are estimated on its
      terraced observables and by configurational estimators (continuous U, W and g on its
      configurations); the smaller bias is used and named. Bias runs take a g(r) frame at
      every sample (analysis.rdf_every 1; --set it for another). Prints the verdict (the cheaper
      engine's setting and the cost ratio with its interval, from --cost-pairs alternated
      runs at the scene's N) and writes DIR/tradeoff.json, tradeoff.csv, tradeoff.png and the
      runs in DIR/runs. It runs both engines, so --set keys of either section apply to that
      engine's runs. Run again, the same command continues where it stopped. Exit status 0:
      a verdict; 1: none.
)",
     R"(  --tolerance OBS=VAL   an observable's tolerance, VAL absolute or VAL% relative; defaults:
                        u 0.5% (of max(|u|, T*)), p 2% (of max(|P|, rho* T*)), d 3%,
                        g 0.02, g_peak 1%, tau_v 3%, tau_o 3%
  --observables LIST    the observables judged (default: all that apply of
                        u,p,d,g,g_peak,tau_v,tau_o)
  --dV LIST             the DMD ladder, in kT (default 1,0.5,0.25,0.125)
  --designs LIST        DMD terraces: uniform, optimal (default both)
  --schemes LIST        SMD splittings: verlet, omelyan, yoshida4 (default all)
  --bias-n N            bodies of the bias runs (default 0: the scene's)
  --max-replicas N      replicas per setting at most (default 32, >= 2)
  --cost-pairs N        alternated cost runs per engine (default 5)
  --budget-cpu-hours H  the CPU budget of the bias runs, all each spent (default 8)
  -j N                  runs at once (default 1)
  --out DIR             the tradeoff's directory (default: out/tradeoff-<scene name>, then the
                        --set keys as for terrace run)
  --frontier            resolve both engines' cheapest settings within, even where one
                        engine is already cheaper than any setting of the other could be
  --quiet               no progress output
)",
     false},
    {"export", R"(  terrace export lammps SCENE.json DIR [--set KEY=VALUE]...
)",
     R"(      Write the scene's model and initial state for LAMMPS (units real): DIR/data.lammps
      (positions, velocities; orientations and angular momenta of ellipsoids), DIR/in.terrace
      (the input deck: lmp -in in.terrace) and, for tabulated pairs, DIR/pair.table. LJ
      spheres: pair_style table of the smoothed g(r)*U_LJ that SMD integrates, fine enough
      that the first frame's U moves by at most 2.5e-7 relative. Gay-Berne: pair_style gayberne and
      fix nve/asphere (the same U; LAMMPS cuts at r_u where terrace switches off smoothly).
      Site molecules: fix rigid/small with site-pair tables (switched by site distance, not
      by the molecules' centres). Prints the first frame's U under both models and every
      difference; the rod potential (rod-lj) and step tables (steps) are refused, naming the
      reason. Files of an earlier export in DIR are replaced.
)",
     R"(  SCENE.json            the scene (experiments/scenes/ holds some)
  DIR                   the directory written (created if need be)
  --set KEY=VALUE       set a scene key by its dotted path, as for terrace run (e.g.
                        --set state.n=4000)
)",
     false},
};

const char* stopNotes =
    R"(SIGINT, SIGTERM and SIGHUP end a run at the next sample with its output written (exit
status 128 + the signal's number; the analysis, accumulated as the run went, is written
too); a third signal ends the process at once.
)";

const char* commonNotes =
    R"(Per-body arrays of 2 MiB and more are mapped on 2-MiB boundaries and advised for transparent
huge pages (fewer TLB misses at large N; TERRACE_HUGE_PAGES=0 in the environment turns the
advice off, for measuring it). summary.json's memory_in_huge_pages_bytes says what the kernel gave.
Before a run (each run of a sweep too) the memory its engine and analysis will need is estimated
from the bodies and settings, and the bytes it will write (trajectory, thermo.csv, restart
files): a run needing more memory than is available (MemAvailable, or less: the room under a
cgroup limit or ulimit -v) or more disk than its output directory's file system has free is
refused, naming the estimate; one that would fill more than half the free space runs with a
warning.
Units: lengths in Angstrom, masses g/mol, energies kJ/mol, times fs/ps on input and output.
)";

const Command* find(const std::string& name) {
    const std::string wanted = name == "analyze" ? "analyse" : name;
    const auto at = std::find_if(std::begin(commands), std::end(commands),
                                 [&](const Command& c) { return wanted == c.name; });
    return at == std::end(commands) ? nullptr : at;
}

bool takesScene(const Command& c) {
    const std::string name = c.name;
    return name == "run" || name == "design" || name == "tradeoff";
}

} // namespace

const std::vector<std::string>& commandNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list;
        for (const Command& c : commands)
            list.emplace_back(c.name);
        return list;
    }();
    return names;
}

std::string commandHelp(const std::string& name) {
    const Command* c = find(name);
    if (c == nullptr) return "";
    std::string text = std::string("Usage:\n") + c->synopsis + c->description + "\nOptions:\n";
    if (takesScene(*c)) text += sceneOptions;
    text += c->options;
    text += "  -h, --help            this help\n";
    if (c->stops) text += std::string("\n") + stopNotes;
    return text + "\n" + commonNotes;
}

std::string generalHelp() {
    std::string text = std::string(header) + "\nUsage:\n";
    for (const Command& c : commands)
        text += std::string(c.synopsis) + c.description;
    text += "  terrace --help | terrace COMMAND --help | terrace help COMMAND\n"
            "      This help, or one command's with all its options.\n\n";
    return text + stopNotes + commonNotes;
}

} // namespace terrace::cli
