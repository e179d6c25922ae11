//! Masked control flow: the same generic shader code means the same thing for one lane,
//! many lanes, dual numbers and intervals.
//!
//! An [`Exec`] carries the *execution mask* — the lanes for which the code being run is
//! live. Writes go through [`Exec::assign`], which blends the new value in only where the
//! mask is set. Regions ([`Exec::if_else`], [`Exec::loop_`]) narrow the mask and skip their
//! body when no lane needs it; [`Exec::break_if`], [`Exec::continue_if`] and
//! [`Exec::return_if`] take lanes out until the enclosing loop / function ends.
//!
//! For `f32` the mask is a `bool`, every region is a plain `if`/`loop` and every blend a
//! plain assignment after inlining. For intervals a condition may be "maybe": both arms run,
//! assignments take the hull, and a loop that does not settle within [`INTERVAL_LOOP_LIMIT`]
//! iterations runs once more with every assignment widened to "unbounded" and exits, which
//! keeps the result conservative and the loop finite.
//!
//! ```
//! use anysl_core::{Exec, ShadingFloat};
//! // Sum of 1/i for i in 1..=n, stopping early once the term is small.
//! fn partial<F: ShadingFloat>(n: F) -> F {
//!     let mut e = Exec::<F>::new();
//!     let (mut i, mut sum) = (F::c(1.0), F::c(0.0));
//!     e.loop_(|e| {
//!         if e.break_if(i.gt(n)) {
//!             return;
//!         }
//!         let term = F::c(1.0) / i;
//!         e.break_if(term.lt(F::c(0.3)));
//!         e.update(&mut sum, |s| s + term);
//!         e.update(&mut i, |i| i + F::c(1.0));
//!     });
//!     sum
//! }
//! assert_eq!(partial(2.0f32), 1.5);
//! assert_eq!(partial(10.0f32), 1.0 + 0.5 + 1.0 / 3.0);
//! ```

use crate::float::{Blend, Mask, ShadingFloat};

/// Iterations after which a loop whose condition is still "maybe" (intervals only) is widened
/// and left.
pub const INTERVAL_LOOP_LIMIT: usize = 64;

/// The execution mask of a running shader and the lanes that have left through `break`,
/// `continue` or `return`.
#[derive(Clone, Copy, Debug)]
pub struct Exec<F: ShadingFloat> {
    active: F::Mask,
    broken: F::Mask,
    continued: F::Mask,
    returned: F::Mask,
    widening: bool,
}

impl<F: ShadingFloat> Default for Exec<F> {
    fn default() -> Self {
        Self::new()
    }
}

impl<F: ShadingFloat> Exec<F> {
    /// Every lane active.
    #[inline(always)]
    #[must_use]
    pub fn new() -> Self {
        Self::with_mask(F::Mask::splat(true))
    }
    /// Only the lanes of `active` are live (e.g. a partly filled packet).
    #[inline(always)]
    #[must_use]
    pub fn with_mask(active: F::Mask) -> Self {
        let no = F::Mask::splat(false);
        Self { active, broken: no, continued: no, returned: no, widening: false }
    }
    /// The lanes currently live.
    #[inline(always)]
    #[must_use]
    pub fn mask(&self) -> F::Mask {
        self.active
    }
    /// True when no lane is live (the rest of a region can be skipped).
    #[inline(always)]
    #[must_use]
    pub fn is_idle(&self) -> bool {
        self.active.none()
    }

    /// `*dst = f(*dst)` in the live lanes (for updates that read the old value).
    #[inline(always)]
    pub fn update<T: Blend<F>>(&self, dst: &mut T, f: impl FnOnce(T) -> T) {
        let v = f(*dst);
        self.assign(dst, v);
    }

    /// `*dst = value` in the live lanes.
    #[inline(always)]
    pub fn assign<T: Blend<F>>(&self, dst: &mut T, value: T) {
        let blended = T::blend(self.active, value, *dst);
        *dst = if <F::Mask as Mask>::THREE_VALUED && self.widening { blended.widen() } else { blended };
    }

    /// Runs `body` with the mask narrowed to `cond`; skipped when no live lane has `cond`.
    #[inline(always)]
    pub fn if_(&mut self, cond: F::Mask, body: impl FnOnce(&mut Self)) {
        let mut body = Some(body);
        self.if_else(
            cond,
            #[inline(always)]
            |e, then| {
                if then {
                    if let Some(b) = body.take() {
                        b(e);
                    }
                }
            },
        );
    }

    /// RSL `if (cond) … else …`, with masks: `arms(e, true)` is the then-arm, `arms(e, false)`
    /// the else-arm (one closure, so both arms may write the same variables). An arm no live
    /// lane needs is not run.
    ///
    /// ```
    /// # use anysl_core::{Exec, ShadingFloat};
    /// let mut e = Exec::<f32>::new();
    /// let mut x = 3.0f32;
    /// e.if_else(x.gt(2.0), |e, then| {
    ///     if then { e.update(&mut x, |x| x - 2.0) } else { e.assign(&mut x, 0.0) }
    /// });
    /// assert_eq!(x, 1.0);
    /// ```
    #[inline(always)]
    pub fn if_else(&mut self, cond: F::Mask, mut arms: impl FnMut(&mut Self, bool)) {
        let saved = self.active;
        let t = saved & cond;
        if t.any() {
            self.active = t;
            arms(self, true);
        }
        let f = saved & !cond;
        if f.any() {
            self.active = f;
            arms(self, false);
        }
        self.active = saved & !(self.broken | self.continued | self.returned);
    }

    /// `cond ? arms(true) : arms(false)` as a value, evaluating only the arms some live lane
    /// needs.
    #[inline(always)]
    pub fn choose<T: Blend<F>>(&mut self, cond: F::Mask, mut arms: impl FnMut(&mut Self, bool) -> T) -> T {
        let live_t = self.active & cond;
        let live_f = self.active & !cond;
        if !live_f.any() {
            return arms(self, true);
        }
        if !live_t.any() {
            return arms(self, false);
        }
        let saved = self.active;
        self.active = live_t;
        let va = arms(self, true);
        self.active = live_f;
        let vb = arms(self, false);
        self.active = saved;
        T::blend(cond, va, vb)
    }

    /// A loop: `body` runs while some lane is live; leave it with [`Exec::break_if`] (a
    /// `while (c)` is `loop_` whose body starts with `if e.break_if(!c) { return; }`). Lanes taken out by
    /// [`Exec::continue_if`] come back at the next iteration.
    #[inline(always)]
    pub fn loop_(&mut self, mut body: impl FnMut(&mut Self)) {
        let outer_active = self.active;
        let outer_broken = self.broken;
        let outer_continued = self.continued;
        let no = F::Mask::splat(false);
        self.broken = no;
        self.continued = no;
        let mut iterations = 0usize;
        loop {
            let live = outer_active & !(self.broken | self.returned);
            if live.none() {
                break;
            }
            self.active = live;
            self.continued = no;
            if <F::Mask as Mask>::THREE_VALUED && iterations >= INTERVAL_LOOP_LIMIT {
                // Not settling: run once more with every write widened, then leave.
                let was = self.widening;
                self.widening = true;
                body(self);
                self.widening = was;
                break;
            }
            body(self);
            iterations += 1;
        }
        self.broken = outer_broken;
        self.continued = outer_continued;
        self.active = outer_active & !(self.returned | outer_broken | outer_continued);
    }

    /// A counted loop `for (init; cond; step)` in masked form: `cond` is tested before each
    /// iteration, `step` runs after the body (also for lanes that `continue`d).
    #[inline(always)]
    pub fn for_<S>(
        &mut self,
        state: &mut S,
        mut cond: impl FnMut(&S) -> F::Mask,
        mut body: impl FnMut(&mut Self, &mut S),
        mut step: impl FnMut(&mut Self, &mut S),
    ) {
        self.loop_(
            #[inline(always)]
            |e| {
                if e.break_if(!cond(state)) {
                    return;
                }
                body(e, state);
                e.end_continue();
                step(e, state);
            },
        );
    }

    /// RSL `break` for the lanes of `cond`: they leave the innermost loop. Returns true when
    /// no lane is left live, so a `while` loop can skip the rest of its body:
    /// `if e.break_if(!cond) { return; }`.
    #[inline(always)]
    pub fn break_if(&mut self, cond: F::Mask) -> bool {
        let leaving = self.active & cond;
        self.broken = self.broken | leaving;
        self.active = self.active & !cond;
        self.active.none()
    }

    /// RSL `continue` for the lanes of `cond`: they skip the rest of this iteration.
    #[inline(always)]
    pub fn continue_if(&mut self, cond: F::Mask) {
        let leaving = self.active & cond;
        self.continued = self.continued | leaving;
        self.active = self.active & !cond;
    }

    /// Brings back the lanes that `continue`d in this iteration (the point where a `for`
    /// loop's step runs).
    #[inline(always)]
    pub fn end_continue(&mut self) {
        self.active = (self.active | self.continued) & !(self.broken | self.returned);
        self.continued = F::Mask::splat(false);
    }

    /// RSL `return` for the lanes of `cond`: they leave the shader (or function).
    #[inline(always)]
    pub fn return_if(&mut self, cond: F::Mask) {
        let leaving = self.active & cond;
        self.returned = self.returned | leaving;
        self.active = self.active & !cond;
    }

    /// Lanes that have executed a `return`.
    #[inline(always)]
    #[must_use]
    pub fn returned(&self) -> F::Mask {
        self.returned
    }

    /// Runs `body` with the mask narrowed to `mask` and restores the mask afterwards (used by
    /// renderers for `illuminance` bodies and by functions with their own `return`).
    #[inline(always)]
    pub fn masked(&mut self, mask: F::Mask, body: impl FnOnce(&mut Self)) {
        let saved = *self;
        let live = self.active & mask;
        if live.none() {
            return;
        }
        let no = F::Mask::splat(false);
        self.active = live;
        self.returned = no;
        body(self);
        let widening = self.widening;
        *self = saved;
        self.widening = widening;
    }

    /// [`Exec::masked`] for a region the caller knows every lane of, i.e. `self.mask() & mask`
    /// is full: `body` runs under a fresh, full mask — a constant the compiler folds, so masked
    /// writes in `body` compile to plain writes — and the mask is restored afterwards.
    #[inline(always)]
    pub fn masked_full(&mut self, body: impl FnOnce(&mut Self)) {
        let mut full = Self::new();
        full.widening = self.widening;
        body(&mut full);
        self.widening = full.widening;
    }
}
