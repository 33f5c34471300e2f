//! Transform lists: translate, rotate, scale, matrix steps.

use super::values::Vec3;
use serde::de::{Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, de};
use std::fmt;

/// One entry of a transform list as written: an inline table that should have exactly one
/// of these keys (checked in `convert`, which then makes a `TransformOp`).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct TransformEntry {
    pub scale: Option<Scale>,
    pub rotate: Option<Rotate>,
    #[serde(default, deserialize_with = "super::values::exact_opt")]
    pub translate: Option<Vec3>,
    #[serde(default, deserialize_with = "super::values::exact_rows_opt")]
    pub matrix: Option<[[f64; 4]; 4]>,
}

impl TransformEntry {
    /// The operation if exactly one key is set, else the keys that are set.
    pub(crate) fn op(&self) -> Result<TransformOp, Vec<&'static str>> {
        let ops = [
            self.scale.map(|s| ("scale", TransformOp::Scale(s))),
            self.rotate.clone().map(|r| ("rotate", TransformOp::Rotate(r))),
            self.translate.map(|t| ("translate", TransformOp::Translate(t))),
            self.matrix.map(|m| ("matrix", TransformOp::Matrix(m))),
        ];
        let mut set: Vec<(&'static str, TransformOp)> = ops.into_iter().flatten().collect();
        if set.len() == 1 {
            Ok(set.remove(0).1)
        } else {
            Err(set.into_iter().map(|(name, _)| name).collect())
        }
    }
}

/// One transform operation.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum TransformOp {
    Scale(Scale),
    Rotate(Rotate),
    Translate(Vec3),
    /// Row-major 4×4; the last row must be 0 0 0 1.
    Matrix([[f64; 4]; 4]),
}

#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct Rotate {
    #[serde(deserialize_with = "super::values::exact")]
    pub axis: Vec3,
    pub degrees: f64,
}

/// `scale = 2.0` or `scale = [1.0, 2.0, 1.0]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Scale {
    Uniform(f64),
    PerAxis(Vec3),
}

impl Scale {
    pub(crate) fn factors(self) -> Vec3 {
        match self {
            Scale::Uniform(s) => [s; 3],
            Scale::PerAxis(v) => v,
        }
    }
}

impl<'de> Deserialize<'de> for Scale {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ScaleVisitor;

        impl<'de> Visitor<'de> for ScaleVisitor {
            type Value = Scale;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number or an array of 3 numbers")
            }

            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Scale, E> {
                Ok(Scale::Uniform(v))
            }

            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Scale, E> {
                Ok(Scale::Uniform(v as f64))
            }

            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Scale, E> {
                Ok(Scale::Uniform(v as f64))
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Scale, A::Error> {
                let mut v = [0.0; 3];
                for (i, slot) in v.iter_mut().enumerate() {
                    *slot =
                        seq.next_element()?.ok_or_else(|| de::Error::invalid_length(i, &self))?;
                }
                if seq.next_element::<de::IgnoredAny>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &self));
                }
                Ok(Scale::PerAxis(v))
            }
        }

        deserializer.deserialize_any(ScaleVisitor)
    }
}
