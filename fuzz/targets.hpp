#pragma once
// The readers of outside input, each as one entry taking the raw bytes a user could hand terrace:
// the fuzzers (libFuzzer, fuzz/CMakeLists.txt) call them on generated inputs, and the regression
// test (fuzz/test_regressions.cpp) on every file kept under fuzz/corpus and fuzz/regressions.
// An entry returns normally when the input was read, or refused with the one-line error terrace
// prints for it (SceneError, IoError, CsvError, ...). Anything else, an exception of another
// type, a crash or a sanitizer report, is a finding.
#include <string_view>

namespace terrace::fuzz {

/// A scene file as `terrace run SCENE --set ...` reads it: leading lines "--set key=value" are the
/// command line's overrides, the rest is the scene's JSON.
void sceneInput(std::string_view bytes);
/// A sweep file, its leading "--set" lines as for sceneInput; relative scene paths resolve against
/// experiments/sweeps, so that the committed sweeps' scenes are found.
void sweepInput(std::string_view bytes);
/// restart.bin as `terrace run --continue DIR` reads it: the CBOR document and the scene it
/// records. An input whose first byte is 0xff is the analysis' state a restart file carries
/// instead, restored into an analysis of 8 samples, 4 lags a level, whose bodies the second
/// byte sets (low three bits, plus two) and whether it has a terracing profile (bit 3). One whose
/// first byte is 0xfe is the sample statistics' state, restored into statistics of 8 + (second
/// byte & 15) samples (bit 4: DMD's impulse virial; bit 5: a heat bath) and summarised.
void restartInput(std::string_view bytes);
/// trajectory.xyz as `terrace analyse DIR` reads it (no scene.json beside it).
void trajectoryInput(std::string_view bytes);
/// Two CSV files as `terrace compare A B` reads them, separated by a line "%%" (without one, the
/// file is compared with itself).
void csvInput(std::string_view bytes);

} // namespace terrace::fuzz
