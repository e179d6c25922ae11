/*
 * screen — the classic RenderMan wire screen. Port of shaders/src/surfaces/screen.rs.
 * Points where mod(s·frequency, 1) < density or mod(t·frequency, 1) < density are
 * wire (plastic lighting, Oi = Os); the rest are holes (Ci = 0, Oi = 0, the renderer
 * continues the ray). Lighting runs only for wire points.
 */
#include "anysl.h"

surface screen(
    uniform float Ka = 0.1;
    uniform float Kd = 0.5;
    uniform float Ks = 0.5;
    uniform float roughness = 0.1;
    uniform color specularcolor = 1;
    uniform float density = 0.25;   /* fraction of each period covered by wire */
    uniform float frequency = 20;)  /* wires per unit of s and t */
{
    Ci = 0;
    Oi = 0;
    if (mod(s * frequency, 1) < density || mod(t * frequency, 1) < density) {
        normal Nf = faceforward(normalize(N), I, N);
        vector V = -normalize(I);
        Ci = Os * anysl_plastic(Nf, V, Cs, Ka, Kd, Ks, roughness, specularcolor);
        Oi = Os;
    }
}
