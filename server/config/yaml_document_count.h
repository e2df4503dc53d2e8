#pragma once
// Counting the documents of a YAML stream without yaml-cpp's LoadAll.
//
// yaml-cpp 0.7 (Debian 12) loops forever in LoadAll on a stray token after a
// document ("{a: 1},", "[x],"): the parser keeps reporting one more empty
// document without consuming the token, and LoadAll keeps appending them,
// growing memory without bound (jbeder/yaml-cpp#1040, fixed upstream by
// PR #1319 after 0.8.0). Found by tests/fuzz/fuzz_body_yaml: a SPAWN command
// could hang rbserver. Asking the parser for at most `limit` documents
// stays bounded whatever the text is.

#include <string>

#include <yaml-cpp/mark.h>

namespace rbsim {

// The number of documents in `text`, counting no further than `limit`
// (>= 1). `lastStart`, if given, receives where the root node of document
// number `limit` starts when there are that many. Throws YAML::Exception on a syntax error
// in the documents it reads, as YAML::Load does.
int countYamlDocuments(const std::string& text, int limit, YAML::Mark* lastStart = nullptr);

}  // namespace rbsim
