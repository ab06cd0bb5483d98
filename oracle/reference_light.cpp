#include "oracle/reference_light.h"

#include "oracle/lights/area_light_kind.h"

namespace so {

ReferenceLight::ReferenceLight(const Light& light, const LocalFrame& frame)
    : sampler_(areaLightKind(light.type).reference(light, frame)) {}

}  // namespace so
