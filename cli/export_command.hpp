#pragma once
// `terrace export lammps SCENE DIR [--set KEY=VALUE]...`: the scene's model and initial state
// written for LAMMPS (cli/lammps_deck.hpp) as DIR/data.lammps, DIR/in.terrace and, for tabulated
// pairs, DIR/pair.table; prints what the deck maps differently from terrace and the initial
// state's potential energy under both models.
#include <filesystem>
#include <string>
#include <vector>

namespace terrace::cli {

struct ExportRequest {
    std::string format;    // "lammps", the only one
    std::string scenePath; // the scene file
    std::filesystem::path dir;
    std::vector<std::string> overrides; // --set
};

/// Writes the files and prints the summary. Throws LammpsRefusal or SceneError before writing
/// anything, IoError (naming the file and the cause) when a file cannot be written.
int exportScene(const ExportRequest& request);

} // namespace terrace::cli
