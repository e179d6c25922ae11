/*
 * starball — the classic starball (the Luxo Jr. ball). Port of
 * shaders/src/surfaces/starball.rs. In spherical coordinates of P (star centres on
 * the ±z axis, +y up): a five-pointed star of angular radius starsize with a tip
 * pointing up, a band |y| <= bandwidth around the ball, the rest ballcolor; plastic
 * lighting, Oi = Os. Like the Rust, P is used as given (no transform to "object").
 */
#include "anysl.h"

surface starball(
    uniform float Ka = 1;
    uniform float Kd = 0.5;
    uniform float Ks = 0.5;
    uniform float roughness = 0.1;
    uniform color specularcolor = 1;
    uniform color starcolor = color (0.90, 0.10, 0.05);
    uniform color bandcolor = color (0.05, 0.20, 0.80);
    uniform color ballcolor = color (1.00, 0.80, 0.05);
    uniform float starsize = 0.45;   /* angular radius of the star's tips, radians */
    uniform float bandwidth = 0.2;)  /* half-height of the band on the unit ball */
{
    normal Nf = faceforward(normalize(N), I, N);
    vector V = -normalize(I);

    vector d = normalize(P);
    /* Polar coordinates around the nearer star centre (+z or -z). */
    float r = acos(min(abs(zcomp(d)), 1));
    float phi = atan(ycomp(d), xcomp(d));
    /* Fold the angle into one half-sector: 0 at a tip, PI/5 at the notch. */
    uniform float sector = 2 * PI / 5;
    float a = abs(mod(phi - (PI / 2 - sector / 2), sector) - sector / 2);
    float qx = r * cos(a);
    float qy = r * sin(a);
    /* Inside the star <=> on the centre's side of the edge from the tip to the notch. */
    uniform float rmax = starsize;
    uniform float rmin = rmax * 0.3819660112501052;   /* sin 18° / sin 126° */
    uniform float vx = rmin * cos(PI / 5);
    uniform float vy = rmin * sin(PI / 5);
    uniform float ex = vx - rmax;
    uniform float ey = vy;

    color Ct;
    if (ex * qy - ey * (qx - rmax) >= 0)
        Ct = starcolor;
    else if (abs(ycomp(d)) <= bandwidth)
        Ct = bandcolor;
    else
        Ct = ballcolor;

    Oi = Os;
    Ci = Os * anysl_plastic(Nf, V, Ct, Ka, Kd, Ks, roughness, specularcolor);
}
