// Where a technique, a plug-in (a bias, a denoiser) or a named method value (pattern=three)
// comes from, and how closely it follows that source (issue 63). A grade under an engine's or a
// paper's name is a claim about their work: every row says whose design it grades and whether it
// is that design as published (`faithful`), a variant of it (`variant`, each deviation listed) or
// a design of our own (`own`). `shadow-oracle techniques --json` lists it, docs/techniques.md is
// generated from it, and the reports mark every row that is not faithful.
//
// Each class gives it beside its parameter table:
//     static Provenance provenance() {
//         return {"three.js r182,
//         src/renderers/shaders/ShaderChunk/shadowmap_pars_fragment.glsl.js"
//                 " (PCFShadowMap)",
//                 Fidelity::Variant, {"point-sampled taps where three.js compares 2x2 in
//                 hardware"}};
//     }
// The anchor names the source as a reader would find it: the engine and its version or commit,
// the file (and function) or the paper and its section. `own` designs name what they build on.
#pragma once

#include <string>
#include <vector>

namespace so {

enum class Fidelity {
    Faithful,  // the source's algorithm and its defaults, constant by constant
    Variant,   // the source's design with the deviations listed
    Own,       // a design of ours (it may build on the anchor)
};

struct Provenance {
    std::string anchor;
    Fidelity fidelity = Fidelity::Own;
    // For a variant: each way it differs from the anchor, one line each. Empty otherwise.
    std::vector<std::string> deviations = {};
};

// One source a row's design draws on: its technique's, or a plug-in's or named method value's it
// chose ("technique pcf", "bias=receiver-plane", "pattern=three").
struct ProvenancePart {
    std::string of;
    Provenance provenance;
};

// The class's provenance(), or an empty one where it has none (the registry tests then fail on its
// missing anchor): the registration macros call it so that a class is registered before it is
// given one.
template <class Class>
auto provenanceOf(int) -> decltype(Class::provenance()) {
    return Class::provenance();
}
template <class Class>
Provenance provenanceOf(long) {
    return {};
}

// "faithful", "variant", "own".
const char* fidelityName(Fidelity f);
// Throws std::invalid_argument (a slip in the code, caught by the registry tests) when the anchor
// is empty, a variant lists no deviation or a faithful or own design lists some; `who` names the
// technique or plug-in in the message.
void checkProvenance(const Provenance& p, const std::string& who);

// The row's fidelity: the farthest of its parts' from their sources (own > variant > faithful);
// faithful for none.
Fidelity combinedFidelity(const std::vector<ProvenancePart>& parts);
// The parts as one provenance (an alias's: basic's and its bias's): the anchors joined by "; ",
// the combined fidelity, and for a variant the variant parts' deviations, each prefixed by its
// part ("bias=receiver-plane: ...") where there are several parts.
Provenance combinedProvenance(const std::vector<ProvenancePart>& parts);

}  // namespace so
