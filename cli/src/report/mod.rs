//! `anysl report`: one self-contained HTML page (plots as inline SVG, pictures as inline
//! base64 PNG) that answers, with measurements, how much accuracy each instantiation gives up
//! for speed, whether the library stays correct on nasty inputs, and whether work a scene
//! does not need is left out.
//!
//! | section | module | what |
//! |---|---|---|
//! | a | [`table1`] | the AnySL paper's Table 1 through `crate::table1::run` (+ JIT rows) |
//! | b | [`accuracy`] | error against time per shader and back end, Pareto plots |
//! | c | [`antialias`] | point sampling vs `Dual`-filtered vs supersampling against 1024 spp |
//! | d | [`intervals`] | interval bound width ÷ sampled range, and its cost |
//! | e | [`leave_out`] | specialization, DCE, derivative activity; lazy compilation |
//! | f | [`stability`] | stiff and extreme cases with their expected outcome |
//!
//! `--quick` runs every section at tiny sizes (the test uses it).

mod accuracy;
mod antialias;
mod intervals;
mod leave_out;
pub mod plot;
mod stability;
mod table1;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Settings of `anysl report`.
#[derive(Clone, Debug)]
pub struct ReportOpts {
    /// Folder of `index.html` (and `summary.txt`).
    pub out: PathBuf,
    /// Tiny sizes everywhere (seconds instead of minutes; figures are not meaningful).
    pub quick: bool,
}

/// Problem sizes, chosen once from [`ReportOpts::quick`].
#[derive(Clone, Copy, Debug)]
pub struct Sizes {
    /// Quick mode.
    pub quick: bool,
    /// Table-1 image side.
    pub table1_size: u32,
    /// Table-1 timed runs.
    pub table1_runs: usize,
    /// Shading points for the error/time rows.
    pub points: usize,
    /// Timed runs (medians).
    pub runs: usize,
    /// Antialiasing image side.
    pub aa_size: u32,
    /// Reference samples per pixel.
    pub aa_ref_spp: u32,
    /// Supersampling rates.
    pub aa_spp: &'static [u32],
    /// Interval boxes per shader and size.
    pub boxes: usize,
    /// Point samples per box.
    pub box_samples: usize,
}

impl Sizes {
    /// The full report (under 5 minutes on 2 cores).
    pub const FULL: Sizes = Sizes {
        quick: false,
        table1_size: 256,
        table1_runs: 3,
        points: 8192,
        runs: 5,
        aa_size: 128,
        aa_ref_spp: 1024,
        aa_spp: &[4, 16, 64],
        boxes: 40,
        box_samples: 256,
    };
    /// Tiny sizes for the test.
    pub const QUICK: Sizes = Sizes {
        quick: true,
        table1_size: 16,
        table1_runs: 1,
        points: 256,
        runs: 1,
        aa_size: 16,
        aa_ref_spp: 64,
        aa_spp: &[4, 16],
        boxes: 3,
        box_samples: 16,
    };
}

/// One section of the page.
pub struct Section {
    /// Anchor (`table1`, `accuracy`, …); the test looks for `id="…"`.
    pub id: &'static str,
    /// Heading.
    pub title: &'static str,
    /// Body HTML.
    pub html: String,
    /// Findings, one line each (printed, and listed at the top of the page).
    pub summary: Vec<String>,
}

/// Writes the report and returns the path of `index.html`.
///
/// # Errors
/// When a section fails or the files cannot be written.
pub fn run(opts: &ReportOpts) -> Result<PathBuf, String> {
    let sz = if opts.quick { Sizes::QUICK } else { Sizes::FULL };
    let start = Instant::now();
    type Part = fn(&Sizes) -> Result<Section, String>;
    let parts: [(&str, Part); 6] = [
        ("a. Table 1", table1::section),
        ("b. error against time", accuracy::section),
        ("c. antialiasing", antialias::section),
        ("d. interval bounds", intervals::section),
        ("e. leaving out", leave_out::section),
        ("f. stability", stability::section),
    ];
    let mut sections = Vec::new();
    for (name, part) in parts {
        let t = Instant::now();
        eprintln!("report: {name} …");
        let mut s = part(&sz)?;
        let secs = t.elapsed().as_secs_f64();
        let _ = write!(s.html, "<p class=\"note\">Section time: {secs:.1} s.</p>");
        eprintln!("report: {name} done in {secs:.1} s");
        for line in &s.summary {
            println!("  {line}");
        }
        sections.push(s);
    }
    let total = start.elapsed().as_secs_f64();
    let html = page(&sections, &sz, total);
    std::fs::create_dir_all(&opts.out).map_err(|e| format!("cannot create {}: {e}", opts.out.display()))?;
    let index = opts.out.join("index.html");
    write_file(&index, &html)?;
    let mut summary = String::new();
    for s in &sections {
        let _ = writeln!(summary, "{}", s.title);
        for line in &s.summary {
            let _ = writeln!(summary, "  - {line}");
        }
    }
    let _ = writeln!(summary, "total: {total:.1} s{}", if sz.quick { " (quick)" } else { "" });
    write_file(&opts.out.join("summary.txt"), &summary)?;
    Ok(index)
}

fn write_file(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

fn page(sections: &[Section], sz: &Sizes, total: f64) -> String {
    let mut h = String::new();
    h.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>anysl report</title>\n<style>\n\
         body{font-family:system-ui,sans-serif;max-width:1280px;margin:1em auto;padding:0 1em;color:#222}\n\
         table{border-collapse:collapse;margin:.6em 0;font-size:13px}td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}\n\
         th{background:#f0f0f0}td:first-child,th:first-child{text-align:left}\n\
         .plots{display:flex;flex-wrap:wrap;gap:6px}.note{color:#666;font-size:13px}\n\
         .grid img{image-rendering:pixelated;width:160px;height:160px}.grid td{text-align:center;font-size:12px}\n\
         .pass{color:#070;font-weight:bold}.fail{color:#b00;font-weight:bold}\n</style></head><body>\n",
    );
    let _ = writeln!(
        h,
        "<h1>anysl report</h1><p>Shaders written once, generic over <code>ShadingFloat</code>, measured as \
         instantiations and back ends. Generated by <code>anysl report{}</code> in {total:.0} s on {} \
         hardware thread(s){}.</p>",
        if sz.quick { " --quick" } else { "" },
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        if cfg!(feature = "jit") { ", built with the LLVM JIT" } else { ", built without the JIT (no JIT rows)" }
    );
    h.push_str("<h2>Findings</h2>\n");
    for s in sections {
        let _ = write!(h, "<h3><a href=\"#{}\">{}</a></h3><ul>", s.id, esc(s.title));
        for line in &s.summary {
            let _ = write!(h, "<li>{}</li>", esc(line));
        }
        h.push_str("</ul>\n");
    }
    for s in sections {
        let _ = write!(h, "<section id=\"{}\"><h2>{}</h2>\n{}\n</section>\n", s.id, esc(s.title), s.html);
    }
    h.push_str("</body></html>\n");
    h
}

/// HTML-escapes text.
#[must_use]
pub fn esc(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// An HTML table from a header and rows of already formatted cells (escaped here).
#[must_use]
pub fn table(head: &[&str], rows: &[Vec<String>]) -> String {
    let mut h = String::from("<table><tr>");
    for c in head {
        let _ = write!(h, "<th>{}</th>", esc(c));
    }
    h.push_str("</tr>\n");
    for r in rows {
        h.push_str("<tr>");
        for c in r {
            let _ = write!(h, "<td>{}</td>", esc(c));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
    h
}

/// Standard base64 (RFC 4648, with padding).
#[must_use]
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n =
            (u32::from(c[0]) << 16) | (u32::from(*c.get(1).unwrap_or(&0)) << 8) | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// An `<img>` with the picture inline as a base64 PNG (8-bit sRGB).
#[must_use]
pub fn img_tag(img: &anysl_renderers::Image, alt: &str) -> String {
    let mut png = Vec::new();
    let enc = image::codecs::png::PngEncoder::new(&mut png);
    let ok =
        image::ImageEncoder::write_image(enc, &img.to_srgb8(), img.width, img.height, image::ExtendedColorType::Rgb8);
    match ok {
        Ok(()) => format!("<img alt=\"{}\" title=\"{0}\" src=\"data:image/png;base64,{}\">", esc(alt), base64(&png)),
        Err(e) => format!("<span>PNG failed: {e}</span>"),
    }
}

/// The median of `v` (NaN for an empty slice).
#[must_use]
pub fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Formats a value in scientific notation with 2 digits (`0` for exact zero).
#[must_use]
pub fn sci(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v:.2e}")
    }
}

/// PSNR in dB for a mean squared error with peak 1 (`inf` for 0).
#[must_use]
pub fn psnr_of_mse(mse: f64) -> f64 {
    if mse <= 0.0 {
        f64::INFINITY
    } else {
        10.0 * (1.0 / mse).log10()
    }
}

/// Formats a PSNR (`inf` for identical).
#[must_use]
pub fn db(v: f64) -> String {
    if v.is_finite() {
        format!("{v:.1}")
    } else {
        "inf".into()
    }
}
