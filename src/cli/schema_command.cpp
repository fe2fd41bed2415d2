#include <iostream>

#include "cli/command_support.h"
#include "cli/commands.h"
#include "scene/scene_schema.h"

namespace coinroll::cli {

void runSchema(const SchemaOptions& options) {
  writeTextOutput("-", "scene schema", [&options](std::ostream& out) {
    if (options.markdown)
      out << scene::schema::toMarkdown();
    else if (options.contract)
      out << scene::schema::toContractMarkdown();
    else
      out << scene::schema::toJson().dump(2) << '\n';
  });
}

}  // namespace coinroll::cli
