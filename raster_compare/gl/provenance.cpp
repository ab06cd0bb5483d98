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
    if (p.anchor.empty())
        throw std::invalid_argument(who + ": provenance has no anchor");
    if (p.fidelity == Fidelity::Variant && p.deviations.empty())
        throw std::invalid_argument(who + ": a variant lists its deviations");
    if (p.fidelity != Fidelity::Variant && !p.deviations.empty())
        throw std::invalid_argument(who + ": only a variant lists deviations");
}

}  // namespace so
