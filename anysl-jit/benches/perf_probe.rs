//! Rough timings for iterating on the JIT without building the CLI (`anysl bench jit` is the
//! benchmark): `cargo bench -p anysl-jit --bench perf_probe -- probe|overhead|spin_x8|dump_ir|compile`.

use anysl_core::points::{shade_points, PointSet, ShadeOut};
use anysl_jit::{compile, JitOptions, JitShader, Variant};
use anysl_shaders::{table1_lights, Light, Surface};
use anysl_simd::{F32x16, F32x8};
use std::path::PathBuf;
use std::time::Instant;

fn rsl_dir() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../shaders/rsl"))
}

fn probe() {
    let set = PointSet::random(1 << 15, 1);
    // `LIGHTS=none` shades without lights (the cost of everything but the light loops).
    let lights = if std::env::var("LIGHTS").is_ok_and(|v| v == "none") { Vec::new() } else { table1_lights() };
    // `NOISE=call` measures the library-call noise instead of the inline IR.
    let inline_noise = Some(std::env::var("NOISE").map_or(true, |v| v != "call"));
    let specialize = std::env::var("SPEC").map_or(true, |v| v != "0");
    let opts = JitOptions { inline_noise, specialize, ..JitOptions::default() };
    for name in ["plastic", "checker", "brick", "wood", "granite", "parquet", "screen", "starball", "venus", "glass"] {
        let path = rsl_dir().join(format!("{name}.sl"));
        let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], opts.clone()).unwrap();
        let t = Instant::now();
        let cs = compile(&jit.module, &jit.values, Variant::X8, &jit.opts).unwrap();
        let ct = t.elapsed().as_secs_f64() * 1e3;
        let _ = jit.variant(Variant::X8);
        let mut out = ShadeOut::new(set.len());
        let aot = Surface::by_name(if name == "plastic" { "phong" } else { name }).unwrap();
        // Interleaved, best of 7 each: drift on a shared machine hits both alike.
        let (mut bj, mut ba) = (f64::MAX, f64::MAX);
        for _ in 0..7 {
            let t = Instant::now();
            shade_points::<F32x8, _, Light>(&jit, &lights, &set, &mut out);
            bj = bj.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            shade_points::<F32x8, _, Light>(&aot, &lights, &set, &mut out);
            ba = ba.min(t.elapsed().as_secs_f64());
        }
        let (j, a) = (set.len() as f64 / bj, set.len() as f64 / ba);
        eprintln!(
            "{name:10} compile {ct:6.1} ms {:?} insts {:?}  jit-x8 {j:.3e} aot-x8 {a:.3e} ratio {:.2}",
            cs.stats.times_ms.iter().map(|(s, t)| format!("{s}={t:.1}")).collect::<Vec<_>>(),
            cs.stats.insts.iter().filter(|(s, _)| s.starts_with("llvm")).map(|(_, n)| *n).collect::<Vec<_>>(),
            j / a
        );
    }
}

/// Cold compile time of each Table-1 shader at x8 (`VARIANT=f32|x4|x16` for another): the
/// median of 9 compiles per stage, and the LLVM instruction counts.
fn compile_times() {
    let variant = match std::env::var("VARIANT").as_deref() {
        Ok("f32") => Variant::F32,
        Ok("x4") => Variant::X4,
        Ok("x16") => Variant::X16,
        _ => Variant::X8,
    };
    let opts = JitOptions::default();
    for name in [
        "constant", "plastic", "checker", "brick", "wood", "granite", "parquet", "screen", "starball", "venus", "glass",
    ] {
        let mut path = rsl_dir().join(format!("{name}.sl"));
        if !path.exists() {
            path = rsl_dir().join("standard").join(format!("{name}.sl"));
        }
        let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], opts.clone()).unwrap();
        let mut cpu = Vec::new();
        let mut runs: Vec<anysl_jit::CompiledShader> = (0..9)
            .map(|_| {
                let t = thread_cpu_ms();
                let c = compile(&jit.module, &jit.values, variant, &opts).unwrap();
                cpu.push(thread_cpu_ms() - t);
                c
            })
            .collect();
        cpu.sort_by(f64::total_cmp);
        let median = |f: &dyn Fn(&anysl_jit::CompiledShader) -> f64, runs: &mut Vec<anysl_jit::CompiledShader>| {
            runs.sort_by(|a, b| f(a).total_cmp(&f(b)));
            f(&runs[runs.len() / 2])
        };
        let stages: Vec<String> = ["llvm-irgen", "optimize", "codegen"]
            .iter()
            .map(|st| {
                let t = median(&|c| c.stats.times_ms.iter().find(|(n, _)| n == st).map_or(0.0, |x| x.1), &mut runs);
                format!("{st}={t:.1}")
            })
            .collect();
        let total = median(&|c| c.stats.total_ms(), &mut runs);
        let insts: Vec<usize> =
            runs[0].stats.insts.iter().filter(|(s, _)| s.starts_with("llvm")).map(|(_, n)| *n).collect();
        eprintln!(
            "{name:10} {:?} compile {total:6.1} ms (cpu {:6.1}) {stages:?} llvm insts {insts:?}",
            variant, cpu[4]
        );
    }
}

/// CPU time of this thread in milliseconds (Linux `CLOCK_THREAD_CPUTIME_ID`): compile times
/// that other processes on the machine do not inflate.
fn thread_cpu_ms() -> f64 {
    extern "C" {
        fn clock_gettime(clock: i32, ts: *mut [i64; 2]) -> i32;
    }
    const CLOCK_THREAD_CPUTIME_ID: i32 = 3;
    let mut ts = [0i64; 2];
    // SAFETY: `ts` is a `struct timespec` (two 64-bit fields on x86-64 Linux).
    unsafe { clock_gettime(CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts[0] as f64 * 1e3 + ts[1] as f64 * 1e-6
}

fn dump_ir() {
    let name = std::env::var("SHADER").unwrap_or_else(|_| "plastic".into());
    let path = rsl_dir().join(format!("{name}.sl"));
    let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], JitOptions::default()).unwrap();
    let cs = anysl_jit::compile_with(&jit.module, &jit.values, Variant::X8, &jit.opts, true).unwrap();
    std::fs::write("/tmp/h6_ir.ll", cs.llvm_ir.unwrap()).unwrap();
}

/// One shader's jit-x8 in a loop, for `perf record` (`SHADER=brick`).
fn spin_x8() {
    let name = std::env::var("SHADER").unwrap_or_else(|_| "plastic".into());
    let set = PointSet::random(1 << 14, 1);
    let lights = table1_lights();
    let mut path = rsl_dir().join(format!("{name}.sl"));
    if !path.exists() {
        path = rsl_dir().join("standard").join(format!("{name}.sl"));
    }
    let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], JitOptions::default()).unwrap();
    let mut out = ShadeOut::new(set.len());
    let aot = std::env::var("AOT").is_ok();
    let s = anysl_shaders::rsl::RslSurface::by_name(&name).unwrap();
    if let Ok(dir) = std::env::var("DUMP_CODE") {
        // For `perf`: a symbol for the JIT code and its bytes (disassemble with
        // `objdump -D -b binary -mi386:x86-64 --adjust-vma=ADDR`).
        let cs = jit.variant(Variant::X8).unwrap();
        let addr = cs.f as usize;
        // Up to the end of the mapping that holds the code.
        let maps = std::fs::read_to_string("/proc/self/maps").unwrap();
        let end = maps
            .lines()
            .filter_map(|l| {
                let (a, b) = l.split_whitespace().next()?.split_once('-')?;
                Some((usize::from_str_radix(a, 16).ok()?, usize::from_str_radix(b, 16).ok()?))
            })
            .find(|&(a, b)| a <= addr && addr < b)
            .unwrap()
            .1;
        let len = end - addr;
        std::fs::write(format!("/tmp/perf-{}.map", std::process::id()), format!("{addr:x} {len:x} jit_shade\n"))
            .unwrap();
        let bytes = unsafe { std::slice::from_raw_parts(addr as *const u8, len) };
        std::fs::write(format!("{dir}/code.bin"), bytes).unwrap();
        std::fs::write(format!("{dir}/addr"), format!("{addr:#x}")).unwrap();
    }
    // `LANES=1` spins the scalar variants instead, `LANES=16` the 16-wide ones.
    let lanes = std::env::var("LANES").map_or(8, |v| v.parse().unwrap_or(8));
    let t = Instant::now();
    let mut calls = 0u64;
    while t.elapsed().as_secs_f64() < 3.0 {
        match (aot, lanes) {
            (true, 1) => shade_points::<f32, _, Light>(&s, &lights, &set, &mut out),
            (false, 1) => shade_points::<f32, _, Light>(&jit, &lights, &set, &mut out),
            (true, 16) => shade_points::<F32x16, _, Light>(&s, &lights, &set, &mut out),
            (false, 16) => shade_points::<F32x16, _, Light>(&jit, &lights, &set, &mut out),
            (true, _) => shade_points::<F32x8, _, Light>(&s, &lights, &set, &mut out),
            (false, _) => shade_points::<F32x8, _, Light>(&jit, &lights, &set, &mut out),
        }
        calls += 1;
    }
    let pts = calls as f64 * set.len() as f64 / t.elapsed().as_secs_f64();
    println!("{name} {} lanes {lanes}: {pts:.3e} points/s", if aot { "aot" } else { "jit" });
}

/// Fixed cost per call: `SHADER` (a `shaders/rsl/standard` or Table-1 name) JIT x8 against its
/// generated-Rust twin (`anysl_shaders::rsl`), 7 interleaved runs, best of each.
fn overhead() {
    let set = PointSet::random(1 << 15, 1);
    let lights = table1_lights();
    for name in ["constant", "matte", "plastic", "metal"] {
        let mut path = rsl_dir().join(format!("{name}.sl"));
        if !path.exists() {
            path = rsl_dir().join("standard").join(format!("{name}.sl"));
        }
        let jit = JitShader::from_file(&path, &[rsl_dir().join("include")], JitOptions::default()).unwrap();
        let _ = jit.variant(Variant::X8);
        let aot = anysl_shaders::rsl::RslSurface::by_name(name).unwrap();
        let mut out = ShadeOut::new(set.len());
        let (mut bj, mut ba) = (f64::MAX, f64::MAX);
        for _ in 0..7 {
            let t = Instant::now();
            shade_points::<F32x8, _, Light>(&jit, &lights, &set, &mut out);
            bj = bj.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            shade_points::<F32x8, _, Light>(&aot, &lights, &set, &mut out);
            ba = ba.min(t.elapsed().as_secs_f64());
        }
        let n = set.len() as f64 / 8.0;
        eprintln!("{name:10} jit {:7.1} ns/call  generated-rust {:7.1} ns/call", bj / n * 1e9, ba / n * 1e9);
    }
}

fn main() {
    // `cargo bench` passes `--bench`; the first other argument names the probe.
    let which = std::env::args().skip(1).find(|a| !a.starts_with('-')).unwrap_or_else(|| "probe".into());
    match which.as_str() {
        "probe" => probe(),
        "overhead" => overhead(),
        "spin_x8" => spin_x8(),
        "dump_ir" => dump_ir(),
        "compile" => compile_times(),
        other => {
            eprintln!("perf_probe: unknown probe `{other}` (choices: probe, overhead, spin_x8, dump_ir, compile)");
            std::process::exit(2);
        }
    }
}
