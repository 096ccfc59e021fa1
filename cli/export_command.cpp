#include "cli/export_command.hpp"
#include "cli/lammps_deck.hpp"
#include "cli/run_command.hpp"
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace terrace::cli {

namespace {

/// Writes text to dir/name through a temporary beside it, renamed into place once complete, so
/// that an interrupted export never leaves half a data file that LAMMPS would read.
void writeFile(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
    const std::filesystem::path path = dir / name, partial = dir / (name + ".partial");
    {
        std::ofstream out(partial, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out)
            throw std::filesystem::filesystem_error("write", partial,
                                                    std::make_error_code(std::errc::io_error));
    }
    std::filesystem::rename(partial, path);
}

} // namespace

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
    writeFile(request.dir, "data.lammps", deck.data);
    if (!deck.table.empty()) writeFile(request.dir, "pair.table", deck.table);
    writeFile(request.dir, "in.terrace", deck.input);

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
    for (const std::string& note : deck.notes)
        std::printf("  differs: %s\n", note.c_str());
    std::printf("  run: cd %s && lmp -in in.terrace\n", request.dir.c_str());
    return 0;
}

} // namespace terrace::cli
