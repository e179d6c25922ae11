//! The eval harness of the RSL conformance suite (`tests/data/rsl/README.md`), shared by every back
//! end's conformance test: the directives at the top of each `tests/data/rsl/conformance/*.sl`, the
//! globals of the 1×1 (or `w × h`) grid, and the check of `// expect:` lines against a shader's
//! outputs.
//!
//! ```
//! use anysl_tests::rsl_harness::{check, parse_directives};
//! let d = parse_directives("// test: t\n// set: Kd=0.5\n// expect: Ci = 0.5, 0.5, 0.5\n// tol: 1e-4\nsurface t() {}");
//! assert_eq!(d.tol, 1e-4);
//! assert!(check(&d, &[("Ci", vec![0.50001, 0.5, 0.5])]).is_ok());
//! assert!(check(&d, &[("Ci", vec![0.6, 0.5, 0.5])]).is_err());
//! ```

use anysl_core::{Globals, ParamValue, ShadingFloat};

/// Default absolute tolerance of an `// expect:` line.
pub const DEFAULT_TOL: f64 = 1e-5;

/// The directives of one conformance program.
#[derive(Clone, Debug, PartialEq)]
pub struct Directives {
    /// `// test:` description.
    pub description: String,
    /// `// global:` overrides in order (`s=0.25`, `N=0,1,0`): name and one or three numbers.
    pub globals: Vec<(String, Vec<f64>)>,
    /// `// set:` parameter overrides in order.
    pub sets: Vec<(String, ParamValue)>,
    /// False after `// lights: none`.
    pub lights: bool,
    /// `// expect: name = values` lines in order.
    pub expects: Vec<(String, Vec<f64>)>,
    /// `// tol:` absolute tolerance ([`DEFAULT_TOL`] when absent).
    pub tol: f64,
    /// `// space: name = 16 numbers`: named coordinate systems, each given by its matrix to
    /// current (row-vector convention, row by row); other names are the identity.
    pub spaces: anysl_core::Spaces,
}

fn numbers(text: &str) -> Option<Vec<f64>> {
    text.split(',').map(|x| x.trim().parse::<f64>().ok()).collect()
}

/// Parses the `// key: value` directives of a conformance program (other lines are ignored).
#[must_use]
pub fn parse_directives(text: &str) -> Directives {
    let mut d = Directives {
        description: String::new(),
        globals: Vec::new(),
        sets: Vec::new(),
        lights: true,
        expects: Vec::new(),
        tol: DEFAULT_TOL,
        spaces: anysl_core::Spaces::default(),
    };
    for line in text.lines() {
        let Some(rest) = line.trim().strip_prefix("//") else { continue };
        let Some((key, value)) = rest.split_once(':') else { continue };
        let value = value.trim();
        match key.trim() {
            "test" => d.description = value.to_string(),
            "global" => {
                for item in value.split_whitespace() {
                    if let Some((n, v)) = item.split_once('=') {
                        if let Some(v) = numbers(v) {
                            d.globals.push((n.trim().to_string(), v));
                        }
                    }
                }
            }
            "set" => {
                if let Some((n, v)) = value.split_once('=') {
                    let pv = match numbers(v) {
                        Some(x) if x.len() == 1 => ParamValue::Float(x[0]),
                        Some(x) if x.len() == 3 => ParamValue::Triple([x[0], x[1], x[2]]),
                        _ => ParamValue::String(v.trim().trim_matches('"').to_string()),
                    };
                    d.sets.push((n.trim().to_string(), pv));
                }
            }
            "lights" => d.lights = value != "none",
            "expect" => {
                if let Some((n, v)) = value.split_once('=') {
                    if let Some(v) = numbers(v) {
                        d.expects.push((n.trim().to_string(), v));
                    }
                }
            }
            "tol" => d.tol = value.parse().unwrap_or(DEFAULT_TOL),
            "space" => {
                if let Some((n, v)) = value.split_once('=') {
                    if let Some(m) = numbers(v).and_then(|m| <[f64; 16]>::try_from(m).ok()) {
                        d.spaces.insert(n.trim(), m);
                    }
                }
            }
            _ => {}
        }
    }
    d
}

/// The globals of grid point `(i, j)` of a `w × h` grid (tests/data/rsl/README.md):
/// `u = (i + ½)/w`, `v = (j + ½)/h`, `s = u`, `t = v`, `du = 1/w`, `dv = 1/h`, `P = (u, v, 0)`,
/// `N = Ng = (0, 0, 1)`, `E = (0, 0, 3)`, `I = P − E`, `dPdu = (1, 0, 0)`, `dPdv = (0, 1, 0)`,
/// `Cs = Os = 1`, then the `// global:` overrides (setting `P` also sets `I = P − E`). With
/// dual numbers, screen x follows u and y follows v: `∂u/∂x = du`, `∂v/∂y = dv`.
#[must_use]
pub fn grid_globals<F: ShadingFloat>(d: &Directives, i: usize, j: usize, w: usize, h: usize) -> Globals<F> {
    anysl_rsl::eval::grid_globals(i, j, w, h, &d.globals)
}

/// The globals of the first point of a `w × h` grid (the whole grid for the usual 1×1), as
/// f64; [`Globals::map`] converts them, [`grid_globals`] gives any point with derivative seeds.
#[must_use]
pub fn eval_globals(d: &Directives, w: usize, h: usize) -> Globals<f64> {
    grid_globals::<f64>(d, 0, 0, w, h)
}

/// Checks every `// expect:` of `d` against `outputs` (name → values of one point). The
/// tolerance is `d.tol` plus 1e-6 relative (for single-precision evaluation of large values).
///
/// # Errors
/// One line per failed expectation: expected and actual values.
pub fn check(d: &Directives, outputs: &[(&str, Vec<f64>)]) -> Result<(), String> {
    let mut errs = Vec::new();
    for (name, want) in &d.expects {
        let Some((_, got)) = outputs.iter().find(|(n, _)| n == name) else {
            errs.push(format!("{name}: expected {want:?}, but the shader has no output `{name}`"));
            continue;
        };
        let ok = got.len() == want.len()
            && want.iter().zip(got).all(|(w, g)| (w - g).abs() <= d.tol + 1e-6 * w.abs() || (w.is_nan() && g.is_nan()));
        if !ok {
            errs.push(format!("{name}: expected {want:?}, got {got:?} (tol {})", d.tol));
        }
    }
    if errs.is_empty() {
        Ok(())
    } else {
        Err(errs.join("; "))
    }
}
