#include "deck/text_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace ballista {

std::string read_input_file(const std::string& path, const std::string& key_path, const std::string& what,
                            std::size_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st))
    throw DeckError(path, 0, 0, key_path, "cannot open " + what + ": " + (ec ? ec.message() : "no such file"));
  if (!fs::is_regular_file(st))
    throw DeckError(path, 0, 0, key_path, what + " is not a regular file (a device, pipe or directory)");
  const auto size = fs::file_size(path, ec);
  if (ec) throw DeckError(path, 0, 0, key_path, "cannot read the size of " + what + ": " + ec.message());
  if (size > max_bytes)
    throw DeckError(path, 0, 0, key_path,
                    what + " has " + std::to_string(size) + " bytes, more than the " + std::to_string(max_bytes >> 20) +
                        " MiB an input file may have");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DeckError(path, 0, 0, key_path, "cannot open " + what + ": " + std::strerror(errno));
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (in.bad() || static_cast<std::size_t>(in.gcount()) != size)
    throw DeckError(path, 0, 0, key_path, "cannot read " + what);
  return text;
}

}  // namespace ballista
