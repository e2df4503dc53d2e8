#include "config/yaml_document_count.h"

#include <sstream>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

namespace rbsim {

namespace {

// Parser events that only note where each document's root node starts
// (where YAML::Node::Mark() would point for that document).
class DocumentStarts : public YAML::EventHandler {
 public:
  int count = 0;
  YAML::Mark lastStart;

  void OnDocumentStart(const YAML::Mark& mark) override {
    ++count;
    lastStart = mark;
    m_awaitingRoot = true;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string&) override {
    node(mark);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    node(mark);
  }
  void OnMapEnd() override {}

 private:
  void node(const YAML::Mark& mark) {
    if (!m_awaitingRoot) return;
    lastStart = mark;
    m_awaitingRoot = false;
  }

  bool m_awaitingRoot = false;
};

}  // namespace

int countYamlDocuments(const std::string& text, int limit, YAML::Mark* lastStart) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DocumentStarts starts;
  while (starts.count < limit && parser.HandleNextDocument(starts)) {
  }
  if (lastStart != nullptr && starts.count == limit) *lastStart = starts.lastStart;
  return starts.count;
}

}  // namespace rbsim
