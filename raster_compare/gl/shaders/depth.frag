// Shadow-map pass: depth only, where the alpha test keeps the surface.
void main() { alphaTest(); }
