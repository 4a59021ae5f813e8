#pragma once
// The deck of `ballista drive` (docs/deck.md, "ballista drive"): one material (the `materials:`
// section of the run decks, read by deck/material_reader) and a `drive:` section holding an
// F-table (a CSV file or inline rows) or a list of strain/stress legs.
#include <cstdint>
#include <string>
#include <vector>

#include "driver/point_driver.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

struct DriveDeck {
  std::string file;  ///< deck path
  MaterialSpec material;
  DriveProgram program;       ///< ready to drive (perturbation already applied)
  std::string table_file;     ///< the F-table file read (path as opened), "" for inline rows or legs
  double scale = 1.0;         ///< drive.scale applied to the table (perturb.hpp)
  double noise = 0.0;         ///< drive.noise applied to the table
  std::uint64_t seed = 0;     ///< drive.seed of the noise
  std::string resolved_yaml;  ///< the deck with every default filled
};

/// Reads and validates a drive deck; `overrides` are --set key.path=value strings as for run
/// decks. A relative table file is resolved against the deck's directory. Every problem is a
/// DeckError naming the file (the deck, or the table file), line, column and key path.
DriveDeck read_drive_deck(const std::string& path, const std::vector<std::string>& overrides = {});

/// Same from text; relative table files are resolved against `base_dir`.
DriveDeck parse_drive_deck(const std::string& yaml_text, const std::string& file_name,
                           const std::vector<std::string>& overrides = {}, const std::string& base_dir = ".");

}  // namespace ballista
