// What contact shadows do in a run (docs/report.md, "Contact shadows"): a shadow-map setting with
// contact=on is paired with the same technique at contact=off and otherwise the same parameters
// (the contact_* parameters aside: they mean nothing when off), on one scene and light; the pair
// says how much peter-panning the march closes and how much false shadow and acne it adds. The
// compare report and the sweep report draw the same table from it.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace so {

struct LightRow;
struct ResultRow;

// The rates contact=on moves (docs/metrics.md, "Contact shadows"), each over counted pixels.
struct ContactRates {
    std::optional<double> peterPanning;  // null without the oracle's occ_dist (`contact` effect)
    std::optional<double> screenBleed;   // null without the raster's V_unfiltered
    std::optional<double> falseShadow;
    std::optional<double> acne;
};
ContactRates contactRatesOf(const LightRow& light);

// One technique setting's result on one light: the row's label, technique and typed parameters
// (every one, defaults included; a setting without `contact`, not a shadow map or an image, is
// never paired) and that light's metrics.
struct ContactSetting {
    const ResultRow* setting;
    const LightRow* light;
};

struct ContactPair {
    std::string offLabel, onLabel;
    ContactRates off, on;
    // off - on: positive when contact=on closes peter-panning; null where it is not measured.
    std::optional<double> peterPanningClosed() const;
    // on - off: positive when contact=on adds screen-space bleed / false shadow / acne.
    std::optional<double> screenBleedAdded() const;
    std::optional<double> falseShadowAdded() const;
    std::optional<double> acneAdded() const;
};

// Every contact=on setting with the first contact=off setting of the same technique and the same
// other parameters, in the order of the on settings; none without such pairs.
std::vector<ContactPair> pairContactSettings(const std::vector<ContactSetting>& settings);

// The pairs as an HTML table (rates to 4 decimals, "–" where not measured), with a one-line
// caption; nothing when `pairs` is empty.
void writeContactTable(std::ostream& o, const std::vector<ContactPair>& pairs);

}  // namespace so
