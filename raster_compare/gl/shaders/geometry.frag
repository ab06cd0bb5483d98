// Camera pass: what each pixel sees, in the conventions of docs/exr-channels.md.
in vec3 v_lsPosition;
flat in vec3 v_lsFaceNormal;
uniform vec3 u_lsEye;
uniform float u_meshId;
layout(location = 0) out vec4 o_position;  // xyz local position, w = 1 (hit)
layout(location = 1) out vec4 o_normal;    // xyz camera-facing geometric normal, w = id.mesh
layout(location = 2) out float o_prim;     // id.prim
void main() {
    alphaTest();
    vec3 n = normalize(v_lsFaceNormal);
    if (dot(n, v_lsPosition - u_lsEye) > 0.0) n = -n;
    o_position = vec4(v_lsPosition, 1.0);
    o_normal = vec4(n, u_meshId);
    o_prim = float(gl_PrimitiveID);
}
