#include "io/pnm_header.hpp"

#include <cctype>
#include <fstream>
#include <string>

namespace fleetmerge {
namespace {

// Next whitespace-separated token, skipping '#' comments that run to the end of the line.
std::optional<std::string> NextToken(std::istream& in) {
  std::string token;
  for (int c = in.get(); c != EOF; c = in.get()) {
    if (c == '#') {
      while (c != EOF && c != '\n' && c != '\r') c = in.get();
      if (!token.empty()) return token;
    } else if (std::isspace(c) != 0) {
      if (!token.empty()) return token;
    } else {
      token.push_back(static_cast<char>(c));
      if (token.size() > 12) return std::nullopt;  // no header field is this long
    }
  }
  return token.empty() ? std::nullopt : std::optional<std::string>(token);
}

std::optional<int> NextInt(std::istream& in) {
  const std::optional<std::string> token = NextToken(in);
  if (!token || token->size() > 9 || token->find_first_not_of("0123456789") != std::string::npos) {
    return std::nullopt;
  }
  return std::stoi(*token);
}

}  // namespace

std::optional<PnmHeader> ReadPnmHeader(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::optional<std::string> magic = NextToken(in);
  if (!magic || magic->size() != 2 || (*magic)[0] != 'P' || (*magic)[1] < '1' ||
      (*magic)[1] > '6') {
    return std::nullopt;
  }
  PnmHeader header;
  header.kind = (*magic)[1];
  const std::optional<int> width = NextInt(in);
  const std::optional<int> height = NextInt(in);
  if (!width || !height) return std::nullopt;
  header.width = *width;
  header.height = *height;
  if (header.kind == '1' || header.kind == '4') {
    header.data_offset = in.eof() ? -1 : static_cast<long long>(in.tellg());
    return header;
  }
  const std::optional<int> maxval = NextInt(in);
  if (!maxval) return std::nullopt;
  header.maxval = *maxval;
  header.data_offset = in.eof() ? -1 : static_cast<long long>(in.tellg());
  return header;
}

}  // namespace fleetmerge
