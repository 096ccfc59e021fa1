#include "cli/export_command.hpp"
#include "cli/lammps_deck.hpp"
#include "cli/run_command.hpp"
#include "core/output_file.hpp"
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace terrace::cli {

int exportScene(const ExportRequest& request) {
    if (request.format != "lammps")
        throw std::invalid_argument("export: no format '" + request.format +
                                    "' (the one there is: lammps)");
    RunRequest run;
    run.scenePath = request.scenePath;
    run.overrides = request.overrides;
    const Scene scene = resolveScene(run);
    const LammpsDeck deck = lammpsDeck(scene); // refusals before anything is written
    std::filesystem::create_directories(request.dir);
    // Each file replaced whole (temporary, rename): an interrupted export leaves no half a data
    // file for LAMMPS to read.
    writeFileAtomically(request.dir / "data.lammps", deck.data);
    if (!deck.table.empty())
        writeFileAtomically(request.dir / "pair.table", deck.table);
    else // an earlier export's table, which this deck does not read
        std::filesystem::remove(request.dir / "pair.table");
    writeFileAtomically(request.dir / "in.terrace", deck.input);

    std::printf(
        "%s: %d atoms (potential %s) written to %s/: data.lammps, in.terrace%s\n",
        scene.name.c_str(), deck.atoms, scene.potential.kind.c_str(), request.dir.c_str(),
        deck.table.empty()
            ? ""
            : (", pair.table (" + std::to_string(deck.tablePoints) + " points a table)").c_str());
    if (std::isfinite(deck.energyTerrace)) {
        const double scale = std::abs(deck.energyTerrace);
        std::printf("  U of the initial state: terrace %.12g kJ/mol, the deck %.12g kJ/mol "
                    "(relative difference %.2g)\n",
                    deck.energyTerrace, deck.energyDeck,
                    scale > 0.0 ? std::abs(deck.energyDeck - deck.energyTerrace) / scale : 0.0);
    }
    for (const std::string& line : deck.mapping)
        std::printf("  mapped: %s\n", line.c_str());
    for (const std::string& note : deck.notes)
        std::printf("  differs: %s\n", note.c_str());
    std::printf("  run: cd %s && lmp -in in.terrace\n", request.dir.c_str());
    return 0;
}

} // namespace terrace::cli
