//! Operation counts of a shader whose counts are known by hand.

use anysl_core::points::{field, shade_points, PointSet, ShadeOut};
use anysl_jit::{JitOptions, JitShader, OpCounts, Variant};
use anysl_shaders::Light;
use anysl_simd::{F32x8, Pair};

/// `x = x * x + t` five times under a uniform loop whose counter is a scalar float.
const PROBE: &str = "
surface count_probe(uniform float n = 5;)
{
    float x = s;
    float i;
    for (i = 0; i < n; i += 1)
        x = x * x + t;
    Ci = color(x, x, x);
    Oi = 1;
}
";

const POINTS: usize = 64;

fn probe(count_ops: bool) -> JitShader {
    JitShader::from_source("count_probe.sl", PROBE, &[], JitOptions { count_ops, ..JitOptions::new() }).unwrap()
}

/// What the probe computes, point by point.
fn expected(set: &PointSet) -> Vec<f32> {
    let (s, t) = (set.field(field::S), set.field(field::T));
    (0..set.len())
        .map(|k| {
            let mut x = s[k];
            for _ in 0..5 {
                x = x * x + t[k];
            }
            x
        })
        .collect()
}

fn packet_shaded(jit: &JitShader, set: &PointSet) -> ShadeOut<f32> {
    let mut out = ShadeOut::new(set.len());
    shade_points::<F32x8, JitShader, Light>(jit, &[], set, &mut out);
    out
}

/// Per 8-lane packet of the per-packet function (`shade`, a mask from the caller), read off
/// its optimized IR: each of the 5 iterations an `fmul`, an `fadd` and the `select` that
/// blends `x` with the caller's mask (15); after the loop the blends of `Ci` (one: the three
/// components are one value) and of `Oi`'s three components (4) — 19 vector operations. The
/// caller's mask is tested once (`icmp ne <8 x i32>`: 1 vector integer operation). The loop
/// counter is a scalar: 6 compares (5 taken, 1 leaving) and 5 increments — 11 scalar
/// operations. No calls.
#[test]
fn per_packet_counts_are_the_hand_counted_ones() {
    let set = PointSet::random(POINTS, 3);
    let packets = (POINTS / 8) as u64;
    let jit = probe(true);
    let counted = packet_shaded(&jit, &set);
    let per_packet = OpCounts { vector: 19, vector_int: 1, scalar: 11, calls: 0 };
    let n = jit.op_counts(Variant::X8).expect("compiled with count_ops");
    assert_eq!(
        n,
        OpCounts { vector: 19 * packets, vector_int: packets, scalar: 11 * packets, calls: 0 },
        "{per_packet:?} per packet"
    );
    assert_eq!(jit.op_counts(Variant::X16), Some(OpCounts::default()), "X16 did not run");

    // Counting changes nothing that is computed: the same bits as without counting, and what
    // the loop computes.
    let plain = packet_shaded(&probe(false), &set);
    assert_eq!(counted.channels, plain.channels);
    assert_eq!(counted.channels[0], expected(&set));
    assert_eq!(probe(false).op_counts(Variant::X8), None);

    // Counts accumulate over calls until reset.
    packet_shaded(&jit, &set);
    assert_eq!(jit.op_counts(Variant::X8).unwrap().vector, 2 * 19 * packets);
    jit.reset_op_counts();
    assert_eq!(jit.op_counts(Variant::X8), Some(OpCounts::default()));
}

/// The points entry runs every lane, so the blends fold away: 10 vector operations per 8-lane
/// packet (5 × `fmul`, `fadd`), the same at four packets per call (`X8x4`: each operation on
/// `<32 x float>` counts 4), whatever LLVM does with the loop counter.
#[test]
fn points_entry_counts_ten_per_packet_at_four_packets_per_call() {
    let set = PointSet::random(POINTS, 5);
    let jit = probe(true);
    let mut out = ShadeOut::new(set.len());
    assert!(jit.shade_point_set::<Pair<Pair<F32x8>>, Light>(&[], &set, &mut out).unwrap());
    let n = jit.op_counts(Variant::X8x4).expect("compiled with count_ops");
    assert_eq!(n.vector, 10 * (POINTS / 8) as u64, "{n:?}");
    assert_eq!(n.calls, 0, "{n:?}");
    assert_eq!(out.channels[0], expected(&set));
}
