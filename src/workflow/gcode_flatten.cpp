// `pkm gcode flatten` as a workflow (workflow/gcode_flatten.hpp).
#include "pkm/workflow/gcode_flatten.hpp"

#include <fmt/format.h>

#include "pkm/io/atomic_file.hpp"

namespace pkm::workflow {

void GcodeFlattenRequest::validate() const {
  interpreter.validate();
  if (!out.empty()) io::checkOverwrite(out, force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
}

GcodeFlattenResult flattenGcode(const GcodeFlattenRequest& request) {
  request.validate();
  const cnc::InterpreterOptions options = request.interpreter.options();
  GcodeFlattenResult result;
  result.flat = cnc::flattenProgram(request.program.text, request.program.name, options);
  if (!request.out.empty())
    io::writeFileAtomic(request.out, result.flat.text, io::Overwrite::kAllow);
  result.note = fmt::format("{} executed blocks written, {} lines{}",
                            result.flat.blocks,
                            result.flat.source_line.size(),
                            result.flat.had_o_words ? "" : " (the program has no O-words)");
  return result;
}

}  // namespace pkm::workflow
