#pragma once
// What `terrace --help` and `terrace COMMAND --help` print: each command's synopsis, what it
// does and its options, and the notes that concern them all (signals, huge pages, units).
#include <string>
#include <vector>

namespace terrace::cli {

/// The commands, in the order the general help lists them.
const std::vector<std::string>& commandNames();

/// `terrace COMMAND --help`: the command's synopsis, description and options, with the notes
/// that concern it; "" for a command there is none of ("analyze" is analyse).
std::string commandHelp(const std::string& command);

/// `terrace --help`: every command's synopsis and description, and the common notes.
std::string generalHelp();

} // namespace terrace::cli
