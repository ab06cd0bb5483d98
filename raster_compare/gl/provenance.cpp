#include "raster_compare/gl/provenance.h"

#include <stdexcept>

namespace so {

const char* fidelityName(Fidelity f) {
    switch (f) {
        case Fidelity::Faithful:
            return "faithful";
        case Fidelity::Variant:
            return "variant";
        case Fidelity::Own:
            return "own";
    }
    return "own";
}

void checkProvenance(const Provenance& p, const std::string& who) {
    if (p.anchor.empty()) throw std::invalid_argument(who + ": provenance has no anchor");
    if (p.fidelity == Fidelity::Variant && p.deviations.empty())
        throw std::invalid_argument(who + ": a variant lists its deviations");
    if (p.fidelity != Fidelity::Variant && !p.deviations.empty())
        throw std::invalid_argument(who + ": only a variant lists deviations");
}

Fidelity combinedFidelity(const std::vector<ProvenancePart>& parts) {
    Fidelity f = Fidelity::Faithful;
    for (const ProvenancePart& p : parts)
        if (static_cast<int>(p.provenance.fidelity) > static_cast<int>(f))
            f = p.provenance.fidelity;
    return f;
}

Provenance combinedProvenance(const std::vector<ProvenancePart>& parts) {
    if (parts.size() == 1) return parts[0].provenance;
    Provenance all;
    all.fidelity = combinedFidelity(parts);
    for (const ProvenancePart& p : parts) {
        all.anchor += (all.anchor.empty() ? "" : "; ") + p.of + ": " + p.provenance.anchor;
        if (all.fidelity == Fidelity::Variant)
            for (const std::string& d : p.provenance.deviations)
                all.deviations.push_back(p.of + ": " + d);
    }
    return all;
}

}  // namespace so
