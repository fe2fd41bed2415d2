#pragma once

#include <string>
#include <string_view>

namespace coinroll::cli {

// Messages quote what users gave (file names, --set values, scene text). A control character among
// them would act on the terminal instead of showing, and a line break would split the one-line
// message a script reads: each is shown as \xNN (a line break as \n), tabs kept.
std::string printable(std::string_view text);

}  // namespace coinroll::cli
