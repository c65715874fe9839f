#include "io/common/json_text.h"

#include <iomanip>
#include <sstream>

namespace talus {

std::string jsonString(const std::string& s) {
  std::ostringstream o;
  o << '"';
  for (char c : s) {
    switch (c) {
    case '"': o << "\\\""; break;
    case '\\': o << "\\\\"; break;
    case '\n': o << "\\n"; break;
    case '\t': o << "\\t"; break;
    default:
      if (static_cast<unsigned char>(c) < 0x20) o << "\\u" << std::hex << std::setw(4) << std::setfill('0') << int(c) << std::dec;
      else o << c;
    }
  }
  o << '"';
  return o.str();
}

} // namespace talus
