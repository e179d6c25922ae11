//! Parameter arrays by name, and lane 0 of a number.

use anysl_core::prelude::*;
use anysl_core::shader::{ParamField, ParamValue};

/// A parameter array as a [`ParamValue`].
#[must_use]
pub fn array_value<T: ParamField>(a: &[T]) -> ParamValue {
    ParamValue::Array(a.iter().map(ParamField::to_value).collect())
}

/// A parameter array from a [`ParamValue`] of exactly `N` elements.
#[must_use]
pub fn array_from_value<T: ParamField + Clone, const N: usize>(v: &ParamValue, old: &[T; N]) -> Option<[T; N]> {
    match v {
        ParamValue::Array(items) if items.len() == N => {
            let mut out = old.clone();
            for (o, i) in out.iter_mut().zip(items) {
                *o = T::from_value(i)?;
            }
            Some(out)
        }
        _ => None,
    }
}

/// Lane 0 of a number (for `format`, loop bounds read as integers, …).
#[inline(always)]
#[must_use]
pub fn lane0<F: ShadingFloat>(x: F) -> f64 {
    x.lane(0)
}
