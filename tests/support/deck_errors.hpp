#pragma once
// The DeckError a deck or an action on it raises, for tests that check its file:line:column, key
// path and message (a missing or different exception is a test failure, not a crash).
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"

namespace ballista::test {

/// Runs f, expects a DeckError and returns it.
inline DeckError deck_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const DeckError& e) {
    return e;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected DeckError, got: " << e.what();
    return DeckError("", 0, 0, "", "wrong exception");
  }
  ADD_FAILURE() << "expected DeckError, nothing thrown";
  return DeckError("", 0, 0, "", "no exception");
}

/// The DeckError of parsing `text` (file name deck.yaml) with `overrides`.
inline DeckError parse_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return deck_error([&] { parse_deck(text, "deck.yaml", overrides); });
}

}  // namespace ballista::test
