//! The register files of a batch ([`Frame`]) and where a value lives in them ([`Loc`]): the
//! data the prepared code, the executor and the built-ins share.

use anysl_core::prelude::*;

/// Where a value or variable lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Loc {
    /// Numeric registers `off .. off + width` (each register holds one `F` per chunk).
    Num {
        /// First register.
        off: u32,
        /// Number of float components (arrays: element width × length).
        width: u32,
    },
    /// A lane mask.
    Mask(u32),
    /// A uniform string (arrays: `len` consecutive strings).
    Str(u32, u32),
    /// Nothing (void).
    None,
}

impl Loc {
    pub(crate) fn off(self) -> u32 {
        match self {
            Loc::Num { off, .. } => off,
            Loc::Mask(i) | Loc::Str(i, _) => i,
            Loc::None => 0,
        }
    }
    pub(crate) fn width(self) -> u32 {
        match self {
            Loc::Num { width, .. } => width,
            _ => 1,
        }
    }
}

/// The register files of one batch: `n` chunks of `F` per register.
pub struct Frame<F: ShadingFloat> {
    pub(crate) n: usize,
    pub(crate) f: Vec<F>,
    pub(crate) m: Vec<F::Mask>,
    pub(crate) s: Vec<String>,
    pub(super) loops: Vec<(Vec<F::Mask>, Vec<F::Mask>)>,
    pub(super) rets: Vec<Vec<F::Mask>>,
    pub(super) widening: bool,
    /// `L` as set by `illuminate`/`solar` (for light shaders whose body never names `L`).
    pub(super) light_l: Vec3<F>,
    /// The surface point a light shader is evaluated for (`Ps`).
    pub(super) light_ps: Vec3<F>,
}

impl<F: ShadingFloat> Frame<F> {
    #[inline(always)]
    pub(crate) fn get(&self, r: u32, k: usize) -> F {
        self.f[r as usize * self.n + k]
    }
    #[inline(always)]
    pub(crate) fn set(&mut self, r: u32, k: usize, v: F) {
        self.f[r as usize * self.n + k] = v;
    }
    #[inline(always)]
    pub(crate) fn vec3(&self, r: u32, k: usize) -> Vec3<F> {
        Vec3::new(self.get(r, k), self.get(r + 1, k), self.get(r + 2, k))
    }
    #[inline(always)]
    pub(crate) fn color(&self, r: u32, k: usize) -> Color<F> {
        Color::new(self.get(r, k), self.get(r + 1, k), self.get(r + 2, k))
    }
    #[inline(always)]
    pub(crate) fn set3(&mut self, r: u32, k: usize, v: [F; 3]) {
        for (i, x) in v.into_iter().enumerate() {
            self.set(r + i as u32, k, x);
        }
    }
    #[inline(always)]
    pub(crate) fn mask(&self, r: u32, k: usize) -> F::Mask {
        self.m[r as usize * self.n + k]
    }
    #[inline(always)]
    pub(crate) fn set_mask(&mut self, r: u32, k: usize, v: F::Mask) {
        self.m[r as usize * self.n + k] = v;
    }
    pub(crate) fn matrix(&self, r: u32, k: usize) -> Matrix4<F> {
        Matrix4 { m: core::array::from_fn(|i| core::array::from_fn(|j| self.get(r + (i * 4 + j) as u32, k))) }
    }
    pub(crate) fn set_matrix(&mut self, r: u32, k: usize, m: &Matrix4<F>) {
        for i in 0..4 {
            for j in 0..4 {
                self.set(r + (i * 4 + j) as u32, k, m.m[i][j]);
            }
        }
    }

    /// Masked write of `w` components starting at `dst` in chunk `k`.
    #[inline(always)]
    pub(crate) fn write(&mut self, dst: u32, k: usize, m: F::Mask, vals: &[F]) {
        let all = m.all() && !self.widening;
        for (i, &v) in vals.iter().enumerate() {
            let r = dst + i as u32;
            let nv = if all { v } else { F::select(m, v, self.get(r, k)) };
            self.set(r, k, if self.widening { <F as Blend<F>>::widen(nv) } else { nv });
        }
    }

    /// Reads the `width` components of a location in chunk `k` (for outputs and tests).
    #[must_use]
    pub fn read(&self, loc: Loc, k: usize) -> Vec<F> {
        match loc {
            Loc::Num { off, width } => (0..width).map(|c| self.get(off + c, k)).collect(),
            Loc::Mask(r) => vec![F::select(self.mask(r, k), F::c(1.0), F::c(0.0))],
            _ => Vec::new(),
        }
    }
}
