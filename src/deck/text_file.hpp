#pragma once
// Reading a deck, table or data file whole, with a size cap (without one, `/dev/zero` as a table
// takes 2 GB before failing). Only regular files are read: a device, FIFO or directory is refused.
#include <cstddef>
#include <string>

namespace ballista {

/// Largest input text file read (decks, F-tables, jet tables): far above any real table.
inline constexpr std::size_t kMaxInputFileBytes = 64u << 20;

/// Contents of `path`; a DeckError naming the file and `key_path` (the deck key that named the file,
/// "" for the deck itself) if it cannot be opened, is not a regular file or exceeds max_bytes.
/// `what` names the file in messages ("the deck file", "the jet table").
std::string read_input_file(const std::string& path, const std::string& key_path, const std::string& what,
                            std::size_t max_bytes = kMaxInputFileBytes);

}  // namespace ballista
