//! Real-world RSL: dialect features of shaders from public collections (ARMan, the RenderMan
//! Companion, BMRT, PRMan's, Aqsis', K-3D's and RManNotes' shader libraries) that the front end
//! and the interpreter must take as they are. Each test is a small snippet in the style of those
//! shaders: it must check, and run through the interpreter on a few points lit by a point light.
//!
//! `cargo test -p anysl-rsl --test real_world -- --ignored corpus` with `RSL_CORPUS=DIR` runs the
//! same check + interpreter pass over every `.sl` under `DIR/shaders` (headers in
//! `DIR/include`) and prints a table — the harness used to measure the pass rate on shader
//! collections kept outside the repository.

use anysl_ad::Dual;
use anysl_core::prelude::*;
use anysl_core::{ParamValue, PointContext, Shader};
use anysl_rsl::back::interp::{release, run_batch, InterpLight, InterpShader, Program};
use anysl_rsl::ir::{Const, Global};
use anysl_rsl::passes::{optimize, PassOptions};
use anysl_rsl::{compile_file_all, compile_source, CompileOptions, Compiled};
use std::path::{Path, PathBuf};
use std::sync::Arc;

const POINT_LIGHT: &str = r#"
light pointlight (float intensity = 1; color lightcolor = 1; point from = point "shader" (0.5, 0.5, 2);
                  string __category = "std"; output float __nonspecular = 0;)
{
    illuminate (from)
        Cl = intensity * lightcolor / (L . L);
}
"#;

fn lights() -> Vec<InterpLight> {
    let c = compile_source("pointlight.sl", POINT_LIGHT, &CompileOptions::default()).expect("point light compiles");
    let m = optimize(c.module, &PassOptions::default());
    vec![InterpLight::new(Arc::new(Program::new(m).expect("point light prepares")))]
}

fn globals<F: ShadingFloat>(i: usize, j: usize, n: usize) -> Globals<F> {
    let d = 1.0 / n as f64;
    let (uu, vv) = ((i as f64 + 0.5) * d, (j as f64 + 0.5) * d);
    let z = F::c(0.0);
    let u = F::c(uu).with_derivs(F::c(d), z);
    let v = F::c(vv).with_derivs(z, F::c(d));
    let p = Vec3::new(u, v, z);
    let e = Vec3::c(0.0, 0.0, 3.0);
    let mut g = Globals::<F>::unit_square(u, v);
    g.P = p;
    g.I = p - e;
    g.E = e;
    g.du = F::c(d);
    g.dv = F::c(d);
    g
}

/// Runs the shader on an `n × n` grid; returns Ci (or P for displacement) of every point.
fn run_points<F: ShadingFloat>(prog: &Program, n: usize, lights: &[InterpLight]) -> Vec<[f64; 3]> {
    let values: Vec<Const> = prog.module.params.iter().map(|p| p.default.clone()).collect();
    let mut out = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let mut ctx = [PointContext::new(globals::<F>(i, j, n), lights)];
            let fr = run_batch::<F, _>(prog, &values, &mut ctx, &[F::Mask::splat(true)]);
            let g = prog.global_loc(Global::Ci).or_else(|| prog.global_loc(Global::P));
            let v = g.map(|l| fr.read(l, 0)).unwrap_or_default();
            let lane = |k: usize| v.get(k).map_or(0.0, |x| x.lane(0));
            out.push([lane(0), lane(1), lane(2)]);
            release(fr);
        }
    }
    out
}

/// Optimizes and interprets a compiled shader; `Err` when the interpreter cannot prepare it.
fn interpret(c: Compiled, n: usize) -> Result<Vec<[f64; 3]>, String> {
    let m = optimize(c.module, &PassOptions::default());
    let derivs = m.uses_derivatives();
    let prog = Program::new(m).map_err(|e| e.to_string())?;
    let lights = lights();
    Ok(if derivs { run_points::<Dual<f32>>(&prog, n, &lights) } else { run_points::<f32>(&prog, n, &lights) })
}

/// Checks `src` (panicking with the rendered diagnostics on errors) and runs it.
#[track_caller]
fn runs(src: &str) -> Vec<[f64; 3]> {
    let c = match compile_source("test.sl", src, &CompileOptions::default()) {
        Ok(c) => c,
        Err(e) => panic!("does not check:\n{e}"),
    };
    match interpret(c, 2) {
        Ok(v) => v,
        Err(e) => panic!("does not run: {e}"),
    }
}

/// The error codes of `src`.
fn error_codes(src: &str) -> Vec<&'static str> {
    match compile_source("test.sl", src, &CompileOptions::default()) {
        Ok(_) => Vec::new(),
        Err(e) => {
            e.diags.items.iter().filter(|d| d.severity == anysl_rsl::diag::Severity::Error).map(|d| d.code).collect()
        }
    }
}

/// Warnings of a file that checks.
fn warning_codes(src: &str) -> Vec<&'static str> {
    match compile_source("test.sl", src, &CompileOptions::default()) {
        Ok(c) => c.warnings.items.iter().map(|d| d.code).collect(),
        Err(e) => panic!("does not check:\n{e}"),
    }
}

fn sl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    let mut v: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    v.sort();
    for p in v {
        if p.is_dir() {
            sl_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "sl") {
            out.push(p);
        }
    }
}

/// The corpus pass: `RSL_CORPUS=DIR cargo test -p anysl-rsl --test real_world -- --ignored corpus --nocapture`.
#[test]
#[ignore = "needs RSL_CORPUS, a shader collection outside the repository"]
fn corpus() {
    let Ok(dir) = std::env::var("RSL_CORPUS") else { return };
    let dir = PathBuf::from(dir);
    let mut files = Vec::new();
    sl_files(&dir.join("shaders"), &mut files);
    let opts = CompileOptions { include_dirs: vec![dir.join("include")], ..CompileOptions::default() };
    let (mut checked, mut ran) = (0, 0);
    for f in &files {
        let rel = f.strip_prefix(&dir).unwrap_or(f).display().to_string();
        // Every shader of the file, as `rslc check` does.
        let all = compile_file_all(f, &opts);
        if let Some(Err(e)) = all.iter().find(|r| r.is_err()) {
            let first = e.to_string().lines().find(|l| l.contains("error")).unwrap_or("?").to_string();
            println!("{rel}\tCHECK-FAIL\t{first}");
            continue;
        }
        checked += 1;
        let mut status = String::from("ok");
        for c in all.into_iter().flatten() {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| interpret(c, 2)));
            match r {
                Ok(Ok(v)) if v.iter().flatten().any(|x| !x.is_finite()) => status = "ok\t(non-finite output)".into(),
                Ok(Ok(_)) => {}
                Ok(Err(e)) => status = format!("RUN-FAIL\t{e}"),
                Err(_) => status = "RUN-PANIC".into(),
            }
        }
        if status.starts_with("ok") {
            ran += 1;
        }
        println!("{rel}\t{status}");
    }
    let n = files.len().max(1);
    println!("{} files: check {checked} ({}%), interpreter {ran} ({}%)", files.len(), 100 * checked / n, 100 * ran / n);
}

// ---- the dialect features ------------------------------------------------------------------

#[test]
fn baseline_plastic_runs() {
    let v = runs(
        r#"surface plastic (float Ka = 1, Kd = .5, Ks = .5, roughness = .1; color specularcolor = 1;)
        {
            normal Nf = faceforward (normalize(N), I);
            Oi = Os;
            Ci = Os * (Cs * (Ka*ambient() + Kd*diffuse(Nf)) + specularcolor * Ks*specular(Nf,-normalize(I),roughness));
        }"#,
    );
    assert!(v.iter().all(|c| c[0] > 0.0 && c[0].is_finite()), "{v:?}");
}

/// ARMan's reflections.h / project.h, PRMan's and BMRT's shaders: `texture (name[3], …)`
/// selects the alpha channel of a map; the name may be a parameter or an expression.
#[test]
fn texture_channel_selection() {
    runs(
        r#"color ReflMap (string reflname; point P; float blur; output float alpha;)
        {
            point Pndc = transform ("NDC", P);
            float x = xcomp(Pndc), y = 1-ycomp(Pndc);
            alpha = float texture (reflname[3], x, y, "blur", blur, "fill", 1);
            return color texture (reflname, x, y, "blur", blur);
        }
        surface t (string mapname = ""; uniform float alphachannel = 3;)
        {
            float a;
            color c = ReflMap (mapname, P, 0, a);
            float e = float environment (mapname[alphachannel], vector (0, 0, 1));
            float w = float texture (mapname[0], s, t);
            Ci = c + a + e + w;
        }"#,
    );
    // Channel selection still needs a float index and a string map name.
    assert_eq!(error_codes(r#"surface t () { Ci = texture ("a.tx"["x"], s, t); }"#), ["E0213"]);
}

/// PRMan 11+ / Aqsis ray-tracing and global-illumination queries: in a point context nothing
/// occludes, there is no indirect light, and rays are camera rays.
#[test]
fn raytracing_queries() {
    let v = runs(
        r#"surface t (string envmap = ""; float samples = 16;)
        {
            normal Ns = normalize(N);
            float depth = -1;
            rayinfo ("depth", depth);
            float occ = occlusion (P, Ns, samples, "maxdist", 10);
            float occ2 = occlusion ("occlusion.sm", P, Ns, 0, "blur", 0.01);
            color ind = indirectdiffuse (P, Ns, samples, "environmentmap", envmap);
            color tr = transmission (P, P + Ns, "samples", 4);
            color ca = caustic (P, Ns);
            Ci = color (occ + occ2 + raylevel() + isshadowray(), 0, 0) + ind + ca + tr * 0.5;
        }"#,
    );
    assert!(v.iter().all(|c| (c[0] - 0.5).abs() < 1e-6 && (c[1] - 0.5).abs() < 1e-6), "{v:?}");
}

/// `i++` in a `for` step (as 3Delight and PRMan 13+ accept): postfix C increments and
/// decrements, with C's values. (Prefix `--b` stays a double negation.)
#[test]
fn increment_decrement() {
    let v = runs(
        r#"surface t ()
        {
            float i, n = 0, k = 5;
            for (i = 0; i < 4; i++)
                n += 1;
            float a = k++;   /* 5, k = 6 */
            float b = k--;   /* 6, k = 5 */
            k--;
            float c = --k;   /* - -k: 4 */
            Ci = color (n, a + b, k + c);
        }"#,
    );
    assert!(v.iter().all(|c| c[0] == 4.0 && c[1] == 11.0 && c[2] == 8.0), "{v:?}");
    // `+ +x` and `a - -b` keep their meaning.
    let v = runs("surface t () { float a = 2, b = 3; Ci = a - -b + + a; }");
    assert!(v.iter().all(|c| c[0] == 7.0), "{v:?}");
}

/// Aqsis' randgrid.sl: `random()` stored into a uniform variable is one uniform number (PRMan
/// semantics), not a varying value.
#[test]
fn uniform_random() {
    runs(
        r#"surface randgrid (float Kd = .5;)
        {
            uniform color c;
            uniform float r = random();
            c = color (random(), random(), random());
            Ci = c * r * Kd;
        }"#,
    );
    // Still an error when mixed with varying values.
    assert_eq!(error_codes("surface t () { uniform float r = random() * s; }"), ["E0206"]);
}

/// Aqsis' light shaders read the surface normal at `Ps` as `Ns`.
#[test]
fn aqsis_ns_in_lights() {
    runs(
        r#"light envlight (float intensity = 1; string filename = "occlusion.sm";)
        {
            float o = occlusion (filename, Ps, Ns, 0, "blur", 0.01);
            Cl = intensity * (1 - o);
        }"#,
    );
    assert_eq!(error_codes("surface t () { Ci = Ns; }"), ["E0200"]);
}

/// ARMan's smoke.sl and cellclouds.sl march with `ss = clamp (ss, 0.005, end - d); d += ss;
/// while (d <= end)`: when the bounds cross at the end of the ray, clamp gives the lower bound
/// (as PRMan does), so the loop ends instead of stepping by 0 forever.
#[test]
fn clamp_with_crossed_bounds_ends_ray_marches() {
    let v = runs(
        r#"volume march (float stepsize = 0.1;)
        {
            float end = 1, d = 0, n = 0;
            float ss = min (stepsize, end - d);
            while (d <= end) {
                ss = clamp (ss, 0.005, end - d);
                d += ss;
                n += 1;
            }
            Ci = color (n, clamp (0.5, 1, 0), clamp (2, 0, 1));
        }"#,
    );
    assert!(v.iter().all(|c| c[0] > 9.0 && c[0] < 13.0 && c[1] == 1.0 && c[2] == 1.0), "{v:?}");
}

/// PRMan's rectanglelight.sl runs uniform sample loops inside `illuminate (Ps + Ns)`, and
/// Liquid's liquiddistant.sl calls `textureinfo` into a uniform array inside `solar`: bodies
/// every point runs are uniform control flow. With a cone, `illuminate` stays varying.
#[test]
fn uniform_assignments_in_light_bodies_without_cone() {
    runs(
        r#"light rect (float samples = 4; output float __nonspecular = 1;)
        {
            uniform float i, n = floor (sqrt (samples));
            uniform float res[2];
            illuminate (Ps + normalize(N)) {
                Cl = 0;
                for (i = 0; i < n; i += 1)
                    Cl += transmission (Ps, point "shader" (i / n, 0, 1));
                Cl /= n;
            }
            solar (vector "shader" (0, 0, 1), 0) {
                textureinfo ("shadow.tx", "resolution", res);
                Cl *= 1;
            }
        }"#,
    );
    // Under a cone the light's body is varying control flow: a uniform assigned there is
    // made varying (W0004).
    assert_eq!(
        warning_codes(
            "light t () { uniform float n = 0; illuminate (point (0,0,0), vector (0,0,1), 0.5) { n += 1; Cl = n; } }"
        ),
        ["W0004"]
    );
}

/// Ivan DeWolf's IDscartissue.sl names a variable `light`: shader-type words are keywords only
/// where a shader definition or a message-passing call (`surface ("Kd", x)`) can start.
#[test]
fn shader_type_words_as_variable_names() {
    let v = runs(
        r#"float f (float surface) { return surface * 2; }
        surface t (float light = 0.25;)
        {
            color dark = 0;
            color volume = color (1, .3, .2);
            float displacement = f (light);
            float kd = 0;
            if (surface ("Kd", kd) == 0)
                kd = 1;
            Ci = mix (dark, volume, displacement * kd);
        }"#,
    );
    assert!(v.iter().all(|c| (c[0] - 0.5).abs() < 1e-6), "{v:?}");
}

/// BMRT's noises.h: `filtered_fBm` keeps `uniform float amp` in a loop whose condition
/// (`fw < 1.0`) is varying. A uniform *local of a function* assigned under varying flow is made
/// varying with a warning (BMRT, Aqsis), and so is one of the shader body.
#[test]
fn function_locals_promoted_to_varying() {
    let src = r#"
        #define filteredsnoise(p,width) ((2 * noise(p) - 1) * (1 - smoothstep (0.2,0.6,width)))
        float filtered_fBm (point p; float filtwidth; uniform float maxoctaves, lacunarity, gain)
        {
            uniform float i;
            uniform float amp = 1;
            varying point pp = p;
            varying float sum = 0, fw = filtwidth;
            for (i = 0;  i < maxoctaves && fw < 1.0;  i += 1) {
                sum += amp * filteredsnoise (pp, fw);
                amp *= gain;  pp *= lacunarity;  fw *= lacunarity;
            }
            return sum;
        }
        displacement castucco (float freq = 1, Km = 0.2;)
        {
            point Pshad = freq * transform ("shader", P);
            float disp = Km * filtered_fBm (Pshad, sqrt (area (Pshad)), 3, 2, 0.6);
            P += disp * normalize (N);
            N = calculatenormal (P);
        }"#;
    runs(src);
    assert_eq!(warning_codes(src), ["W0004", "W0004"]); // `amp` and the counter `i`
                                                        // Output parameters keep the rule: the caller's variable is uniform.
    assert_eq!(
        error_codes("void f (output uniform float u) { if (s > 0.5) u = 1; } surface t () { uniform float x; f (x); }"),
        ["E0214"]
    );
    // A shader-body local: made varying, and each point keeps its own value (s = 0.25, 0.75).
    let src = "surface t () { uniform float u = 0; if (s > 0.5) u = 1; Ci = u; }";
    assert_eq!(warning_codes(src), ["W0004"]);
    let v = runs(src);
    assert_eq!(v.iter().map(|c| c[0]).collect::<Vec<_>>(), [0.0, 1.0, 0.0, 1.0]);
}

// ---- what period compilers accepted (issue 23, item 6) ------------------------------------------

/// `vector xdir = normalize(dPdu)`, `color c = Cs`: a default that is not a constant is
/// computed when the shader runs (W0006), unless the parameter is given a value.
#[test]
fn computed_parameter_defaults() {
    let src = r#"surface t (vector dir = normalize (dPdu) * 2; float w = du * 3; color c = Cs * 0.5;)
        {
            Ci = color (xcomp (dir), w, comp (c, 0));
        }"#;
    assert_eq!(warning_codes(src), ["W0006", "W0006", "W0006"]);
    // The harness grid: dPdu = (1, 0, 0), du = 1/2, Cs = 1.
    for c in runs(src) {
        assert!((c[0] - 2.0).abs() < 1e-6 && (c[1] - 1.5).abs() < 1e-6 && (c[2] - 0.5).abs() < 1e-6, "{c:?}");
    }
    // A value given for `w` replaces its default; the others still compute theirs.
    let c = compile_source("t.sl", src, &CompileOptions::default()).expect("checks");
    let prog = Arc::new(Program::new(optimize(c.module, &PassOptions::default())).expect("prepares"));
    let mut shader = InterpShader::new(prog.clone());
    shader.set_param("w", &ParamValue::Float(7.0)).expect("w is a parameter");
    let mut ctx = [PointContext::new(globals::<Dual<f32>>(0, 0, 2), &[] as &[InterpLight])];
    let fr = run_batch::<Dual<f32>, _>(&prog, &shader.values, &mut ctx, &[Mask::splat(true)]);
    let ci = fr.read(prog.global_loc(Global::Ci).expect("Ci"), 0);
    let got: Vec<f64> = ci.iter().map(|x| x.lane(0)).collect();
    release(fr);
    assert_eq!(got, [2.0, 7.0, 0.5]);
    // Specialized to given values (`rslc ir --set`): the given string keeps its value (its
    // flag is folded to 0), the unlisted one computes its default.
    let src = r#"surface t (string a = concat ("x", "y"); string b = concat ("p", "q");) { Ci = match ("^z", a) + 2 * match ("^p", b); }"#;
    let c = compile_source("t.sl", src, &CompileOptions::default()).expect("checks");
    let opts = PassOptions {
        specialize: vec![("a".into(), Const::Str("zz".into()))],
        specialize_defaults: true,
        ..PassOptions::default()
    };
    let prog = Program::new(optimize(c.module, &opts)).expect("prepares");
    let mut ctx = [PointContext::new(globals::<f32>(0, 0, 2), &[] as &[InterpLight])];
    // (A parameter the shader stores into is not folded: the instance passes the value too.)
    let mut values: Vec<Const> = prog.module.params.iter().map(|p| p.default.clone()).collect();
    prog.module.set_param_value(&mut values, 0, Const::Str("zz".into()));
    let fr = run_batch::<f32, _>(&prog, &values, &mut ctx, &[Mask::splat(true)]);
    let ci = fr.read(prog.global_loc(Global::Ci).expect("Ci"), 0);
    let got: Vec<f64> = ci.iter().map(|x| x.lane(0)).collect();
    release(fr);
    assert_eq!(got, [3.0, 3.0, 3.0]);
}

/// `0.5f`, `1.f`: C float suffixes, read as the number with a warning (W0005); other letters
/// after a number stay an error.
#[test]
fn float_suffixes() {
    let src = "surface t () { Ci = color (0.5f, 1.f, 2e-1F); }";
    assert_eq!(warning_codes(src), ["W0005", "W0005", "W0005"]);
    assert!(runs(src).iter().all(|c| *c == [0.5, 1.0, 0.2f32 as f64]), "{:?}", runs(src));
    assert_eq!(error_codes("surface t () { Ci = 0.5q; }"), ["E0004"]);
    assert_eq!(error_codes("surface t () { Ci = 0.5ff; }"), ["E0004"]);
}

/// Gamma with `pow (Ct, 1/2.2)`: colour powers by a float and by a colour, per component.
#[test]
fn colour_powers() {
    let v =
        runs("surface t () { Ci = pow (color (0.25, 0.5, 4) * Cs, 0.5) + pow (color (2, 3, 4), color (2, 1, 0.5)); }");
    for c in v {
        let want = [0.5 + 4.0, 0.5f64.sqrt() + 3.0, 2.0 + 2.0];
        assert!(c.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-5), "{c:?}");
    }
    assert_eq!(error_codes("surface t () { Ci = pow (P, 2); }"), ["E0202"]);
}

/// Pixie's and Aqsis' area lights set `N` before `illuminate (P, N, PI/2)` (W0007); an
/// `illuminance` loop in a light shader is checked but never runs (W0008); PRMan's area-shadow
/// option `"source"` with its four points is ignored (W0008).
#[test]
fn light_shader_leniencies() {
    let area = r#"light arealight (float intensity = 1; color lightcolor = 1;)
        {
            N = normalize (N);
            illuminate (P, N, PI/2) {
                Cl = intensity * lightcolor * (N . normalize (L)) / (L . L);
            }
        }"#;
    assert_eq!(warning_codes(area), ["W0007"]);
    runs(area);
    let looped = r#"light t (float k = 1;)
        {
            color seen = 0;
            illuminance (P) { seen += 1; }
            solar () { Cl = k + seen; }
        }"#;
    assert_eq!(warning_codes(looped), ["W0008"]);
    let c = compile_source("t.sl", looped, &CompileOptions::default()).expect("checks");
    let mut loops = 0;
    anysl_rsl::ir::walk(&c.module.func.body, &mut |n| {
        loops += usize::from(matches!(n, anysl_rsl::ir::Node::Illuminance { .. }))
    });
    assert_eq!(loops, 0, "the loop is not emitted");
    let source = r#"light t (string maplist = ""; point p0 = 0, p1 = 0, p2 = 0, p3 = 0;)
        {
            illuminate (point (0, 0, 1)) {
                Cl = 1 - shadow (maplist, Ps, "source", p0, p1, p2, p3, "samples", 4, "bias", 0.01);
            }
        }"#;
    assert_eq!(warning_codes(source), ["W0008"]);
    runs(source);
    // Pixie's mirror normalizes I in place (W0007); Ng stays read-only, N in imagers does not
    // exist, and `illuminance` is still wrong in displacement shaders.
    let mirror = "surface t () { I = normalize (I); Ci = color (I . I); }";
    assert_eq!(warning_codes(mirror), ["W0007"]);
    assert!(runs(mirror).iter().all(|c| (c[0] - 1.0).abs() < 1e-6));
    assert_eq!(error_codes("surface t () { Ng = N; }"), ["E0220"]);
    assert_eq!(error_codes("light t () { I = 0; solar () { Cl = 1; } }"), ["E0220"]);
    assert_eq!(error_codes("displacement t () { illuminance (P) { } }"), ["E0211"]);
}

/// PRMan 13's `arraylength`: a constant for the fixed-size arrays of RSL here.
#[test]
fn array_lengths() {
    let v = runs(
        r#"float total (float a[]) { float i, t = 0; for (i = 0; i < arraylength (a); i += 1) t += a[i]; return t; }
        surface t () { float a[3] = {1, 2, 3}; Ci = color (arraylength (a), total (a), 0); }"#,
    );
    assert!(v.iter().all(|c| *c == [3.0, 6.0, 0.0]), "{v:?}");
    assert_eq!(error_codes("surface t () { Ci = arraylength (s); }"), ["E0202"]);
}

/// A file of several shaders: `rslc check` checks each (PRMan's `shader` compiles them all),
/// and an error in one of them is reported as that shader's.
#[test]
fn several_shaders_in_one_file() {
    let dir = std::env::temp_dir().join(format!("anysl-several-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let f = dir.join("pair.sl");
    std::fs::write(&f, "surface one () { Ci = 1; }\nlight two () { solar () { Cl = 1; } }\n").expect("write");
    let all = anysl_rsl::compile_file_all(&f, &CompileOptions::default());
    let names: Vec<String> = all.iter().map(|r| r.as_ref().expect("checks").module.name.clone()).collect();
    assert_eq!(names, ["one", "two"]);
    std::fs::write(&f, "surface one () { Ci = 1; }\nsurface two () { Ci = nosuch; }\n").expect("write");
    let all = anysl_rsl::compile_file_all(&f, &CompileOptions::default());
    assert!(all[0].is_ok() && all[1].is_err());
    // One named shader, as before.
    let one = CompileOptions { shader: Some("one".into()), ..CompileOptions::default() };
    assert_eq!(anysl_rsl::compile_file_all(&f, &one).len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Pixie's shadowarea.sl: `visibility (Ps, P)` is PRMan's `transmission` (W0009); outside a
/// scene nothing blocks, so the light is unshadowed.
#[test]
fn pixie_visibility() {
    let src = r#"light shadowarea (float intensity = 1; color lightcolor = 1;)
        {
            N = normalize (N);
            illuminate (P, N, PI/2) {
                Cl = visibility (Ps, P) * intensity * lightcolor * (N . normalize (L)) / (L . L);
            }
        }"#;
    assert_eq!(warning_codes(src), ["W0007", "W0009"]);
    runs(src);
    assert_eq!(error_codes("surface t () { Ci = visibility (P); }"), ["E0203"]);
}

/// The RenderMan Companion's windowhighlight (listing 16.20) reads `Ps` in a surface shader:
/// read as `P` (W0009). Light-only globals stay errors there.
#[test]
fn ps_in_a_surface_shader() {
    let src = "surface t () { Ci = color (Ps - P) + 0.5; }";
    assert_eq!(warning_codes(src), ["W0009"]);
    assert!(runs(src).iter().all(|c| *c == [0.5, 0.5, 0.5]));
    assert_eq!(error_codes("surface t () { Ci = Cl; }"), ["E0211"]);
    assert_eq!(error_codes("displacement t () { P = Ps; }"), ["E0211"]);
}

/// Aqsis' point-based GI examples and PRMan 13: `bake3d` and `texture3d` are checked and answered
/// as with no point cloud (W0008): 0, outputs unchanged.
#[test]
fn point_cloud_calls() {
    let src = r#"surface t (string cloud = "";)
        {
            normal Nn = normalize (N);
            float ok = bake3d (cloud, "", P, Nn, "_area", area (P), "_radiosity", Cs, "interpolate", 1);
            color rad = 0.25;
            float found = texture3d (cloud, P, Nn, "_radiosity", rad);
            Ci = color (ok, found, comp (rad, 0));
        }"#;
    assert_eq!(warning_codes(src), ["W0008", "W0008"]);
    assert!(runs(src).iter().all(|c| *c == [0.0, 0.0, 0.25]));
    assert_eq!(error_codes("surface t () { float x = bake3d (\"f\", \"\", P); }"), ["E0203"]);
    assert_eq!(error_codes("surface t () { float x = texture3d (\"f\", P, N, \"a\", 1); }"), ["E0212"]);
    assert_eq!(error_codes("surface t () { float x = bake3d (\"f\", \"\", P, N, 3, 1); }"), ["E0204"]);
}

/// Preprocessor forms of C compilers' cpp: variadic macros (`...`, `__VA_ARGS__`), `#warning`
/// (a warning, W0010), `#ident` and `#sccs` (ignored).
#[test]
fn preprocessor_forms() {
    let src = r#"#ident "$Id: t.sl 1.1$"
        #warning "old file"
        #define DBG(fmt, ...) printf (fmt, __VA_ARGS__)
        #define SUM(...) max (__VA_ARGS__)
        #define ONE(x, ...) (x)
        surface t () { DBG ("%f %f\n", s, t); Ci = SUM (1, 2) + ONE (3) + ONE (4, 5, 6); }"#;
    assert_eq!(warning_codes(src), ["W0010"]);
    assert!(runs(src).iter().all(|c| *c == [9.0, 9.0, 9.0]), "{:?}", runs(src));
    assert_eq!(error_codes("#define F(a, ...., b) a\nsurface t () { }"), ["E0011"]);
    assert_eq!(error_codes("#define F(a, b, ...) a\nsurface t () { Ci = F (1); }"), ["E0013"]);
}

/// Advanced RenderMan's lensflare draws uniform random numbers inside an illuminance loop: a
/// uniform counter assigned there, and a uniform function reading it. One light reaches every
/// point here, so the counter ends at 2 draws per point, the same on all.
#[test]
fn uniform_counter_in_illuminance() {
    let v = runs(
        r#"surface t (float seed = 143;)
        {
            uniform float nrand = 0;
            uniform float urand () { extern uniform float nrand, seed; nrand += 1; return cellnoise (nrand, seed); }
            float sum = 0;
            illuminance (P, vector (0, 0, 1), PI / 2) {
                nrand = 0;
                uniform float a = urand ();
                sum += a + urand ();
            }
            Ci = color (nrand, sum, 0);
        }"#,
    );
    assert!(v.iter().all(|c| c[0] == 2.0 && c[1] == v[0][1]), "{v:?}");
}
