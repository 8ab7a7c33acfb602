// The JSON forms of results.json's parts (results.cpp), for the files that carry rows and machine
// blocks besides results.json itself: the run journal and the row worker's channel.
#pragma once

#include <nlohmann/json.hpp>

#include "harness/results/results.h"

namespace sdb {

void to_json(nlohmann::json& j, const TimeStats& t);
void from_json(const nlohmann::json& j, TimeStats& t);
void to_json(nlohmann::json& j, const RunRow& r);
void from_json(const nlohmann::json& j, RunRow& r);
void to_json(nlohmann::json& j, const MachineInfo& m);
void from_json(const nlohmann::json& j, MachineInfo& m);

// One line, no newline inside; text that is not UTF-8 (a file name, a library's message) replaced
// rather than refused: a row is never lost to its message.
std::string one_line(const nlohmann::json& j);

}  // namespace sdb
