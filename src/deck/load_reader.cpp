#include "deck/load_reader.hpp"

#include "deck/body_ref.hpp"
#include "points/load_registry.hpp"

namespace ballista {

namespace {

/// A load's entry as its kind reads it: DeckNode's checks, with vectors of the run's dimension and
/// bodies checked against the deck's.
class DeckLoadEntry final : public LoadEntry {
 public:
  DeckLoadEntry(DeckNode& node, const Scenario& sc) : node_(node), sc_(sc) {}

  std::string body(bool required) override { return read_body_ref(node_, sc_, required); }
  double number(const std::string& key, const NumberRange& range) override { return node_.number(key, range); }
  double number(const std::string& key, double fallback, const NumberRange& range) override {
    return node_.number(key, fallback, range);
  }
  Vec3 vector(const std::string& key) override { return node_.vector(key, components()); }
  Vec3 vector(const std::string& key, const Vec3& fallback) override {
    return node_.vector(key, fallback, components());
  }
  std::string word(const std::string& key, const std::vector<std::string>& choices) override {
    return node_.choice(key, choices);
  }
  std::string string(const std::string& key) override { return node_.string(key); }
  std::string string(const std::string& key, const std::string& fallback) override {
    return node_.string(key, fallback);
  }
  bool boolean(const std::string& key, bool fallback) override { return node_.boolean(key, fallback); }
  LoadCurve curve() override { return read_load_curve(node_); }
  [[noreturn]] void fail(const std::string& key, const std::string& message) override { node_.fail(key, message); }
  const Scenario& scenario() const override { return sc_; }

 private:
  DeckNode& node_;
  const Scenario& sc_;
  int components() const { return sc_.simulation.dimension == Dimension::ThreeD ? 3 : 2; }
};

}  // namespace

void read_loads(DeckNode& root, Scenario& sc, std::map<std::string, Vec3>& equilibrium_stress) {
  std::vector<std::string> kinds;
  for (const LoadFactory& f : load_registry()) kinds.push_back(f.name);
  DeckNode ls = root.list("loads", false);
  for (size_t i = 0; i < ls.size(); ++i) {
    DeckNode l = ls.element(i);
    LoadSpec load;
    load.mark = l.mark();
    load.type = l.choice("type", kinds);
    DeckLoadEntry entry(l, sc);
    LoadReading r = find_load(load.type)->read(entry, load);
    if (r.prestress && r.equilibrium_stress && !r.loads.empty()) {
      BodySpec& body = sc.bodies[static_cast<size_t>(body_index(sc, r.loads.front().body))];
      if (body.prestress)
        l.fail("prestress", "body '" + body.name + "' is already prestressed by an earlier load");
      if (body.initial_state != "none")
        l.fail("prestress", "body '" + body.name + "' starts in initial_state " + body.initial_state +
                                "; a prestress would overwrite it");
      body.prestress = *r.equilibrium_stress;
    }
    l.finish();
    if (r.equilibrium_stress && !r.loads.empty()) equilibrium_stress[r.loads.front().body] = *r.equilibrium_stress;
    for (LoadSpec& s : r.loads) sc.loads.push_back(std::move(s));
  }
}

LoadCurve read_load_curve(DeckNode& l) {
  LoadCurve c;
  const YAML::Node v = l.raw("curve");
  YAML::Node out(YAML::NodeType::Sequence);
  out.SetStyle(YAML::EmitterStyle::Flow);
  if (v.IsDefined() && !v.IsNull()) {
    const std::string what = "a list of [time, scale] pairs with strictly increasing times";
    if (!v.IsSequence()) l.fail("curve", "expected " + what);
    for (size_t i = 0; i < v.size(); ++i) {
      const YAML::Node p = v[i];
      const std::string path = l.child_path("curve") + "." + std::to_string(i);
      if (!p.IsSequence() || p.size() != 2)
        deck_fail(l.context(), path, p.Mark(), "expected a [time, scale] pair (list of 2 numbers)");
      double tv[2];
      for (int k = 0; k < 2; ++k) {
        const YAML::Node x = p[k];
        double value = 0.0;
        if (!scalar_number(x, value))
          deck_fail(l.context(), path + "." + std::to_string(k), x.Mark(),
                    "expected a number, got " +
                        (x.IsScalar() ? "'" + shorten(x.Scalar()) + "'" : std::string("a list or map")));
        tv[k] = value;
      }
      if (!c.t.empty() && !(tv[0] > c.t.back()))
        deck_fail(l.context(), path + ".0", p[0].Mark(),
                  "expected times strictly increasing; " + format_number(tv[0]) + " follows " +
                      format_number(c.t.back()));
      c.t.push_back(tv[0]);
      c.v.push_back(tv[1]);
      YAML::Node pair(YAML::NodeType::Sequence);
      pair.SetStyle(YAML::EmitterStyle::Flow);
      pair.push_back(format_number(tv[0]));
      pair.push_back(format_number(tv[1]));
      out.push_back(pair);
    }
  }
  l.set_resolved("curve", out);
  return c;
}

}  // namespace ballista
