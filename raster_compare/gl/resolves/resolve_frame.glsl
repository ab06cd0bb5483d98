// The resolves' shared inputs (resolves/resolve_frame.h) and the one reprojection every history
// uses. Textures in GL's row order; every fetch a tap of the work counts (SO_TAP).
uniform sampler2D u_visibility;    // this frame's V (the light's target)
uniform sampler2D u_position;      // xyz local position, w 1 where hit
uniform sampler2D u_normal;        // xyz camera-facing normal, w id.mesh
uniform sampler2D u_prevHistory;   // the resolve's own history of the frame before
uniform sampler2D u_prevPosition;  // the frame before's local positions, w id.mesh + 1 (0: none)
uniform int u_haveHistory;
uniform mat4 u_prevClipFromLocal;  // the frame before's camera, unjittered, its local frame
uniform vec3 u_prevLsEye;
uniform vec3 u_prevLsForward;
uniform float u_prevPixelScale;
layout(std430, binding = 0) readonly buffer Motion {
    mat4 u_prevLocalFromLocal[];  // per mesh: this frame's local point to the frame before's
};
layout(location = 0) out vec4 o_history;
layout(location = 1) out float o_visibility;

float visibilityAt(ivec2 q) {
    SO_TAP(1, VISIBILITY_TEXEL_BYTES);
    return texelFetch(u_visibility, q, 0).r;
}
vec4 positionAt(ivec2 q) {
    SO_TAP(1, POSITION_TEXEL_BYTES);
    return texelFetch(u_position, q, 0);
}
vec4 normalAt(ivec2 q) {
    SO_TAP(1, NORMAL_TEXEL_BYTES);
    return texelFetch(u_normal, q, 0);
}
bool inside(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
}

// Where the point lsP of mesh `mesh` stood in the frame before: its local point there (xyz) and
// its pixel position there (pixel units, (0, 0) the lower-left corner); w < 0 behind the camera.
struct Reprojected {
    vec3 prevLs;
    vec2 pixel;
    bool inFront;
};
Reprojected reproject(vec3 lsP, int mesh) {
    Reprojected r;
    r.prevLs = (u_prevLocalFromLocal[mesh] * vec4(lsP, 1.0)).xyz;
    vec4 clip = u_prevClipFromLocal * vec4(r.prevLs, 1.0);
    r.inFront = clip.w > 0.0;
    r.pixel = (clip.xy / max(clip.w, 1e-30) * 0.5 + 0.5) * vec2(textureSize(u_prevHistory, 0));
    return r;
}
// A pixel's size at the frame before's point (its depth along that camera's axis, as
// time/shadow_history.h measures it).
float prevFootprint(vec3 prevLs) {
    return u_prevPixelScale * dot(prevLs - u_prevLsEye, u_prevLsForward);
}
