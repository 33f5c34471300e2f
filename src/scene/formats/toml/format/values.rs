//! Plain values of the TOML format, and the fixed-length arrays they are read as: exactly
//! as long as the field says. (The `toml` crate hands a longer array to serde's `[T; N]`,
//! which takes the first N and drops the rest unseen: `resolution = [8, 8, "junk"]`
//! rendered 8 × 8.)

use serde::de::{Deserialize, Deserializer, Error, IgnoredAny, SeqAccess, Visitor};
use std::marker::PhantomData;

pub(crate) type Vec3 = [f64; 3];

/// `[T; N]`, read from an array of exactly N values.
pub(crate) struct Exact<T, const N: usize>(pub [T; N]);

impl<'de, T: Deserialize<'de>, const N: usize> Deserialize<'de> for Exact<T, N> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Values<T, const N: usize>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>, const N: usize> Visitor<'de> for Values<T, N> {
            type Value = Exact<T, N>;

            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                write!(f, "an array of length {N}")
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
                let mut values = Vec::with_capacity(N);
                while values.len() < N {
                    match seq.next_element()? {
                        Some(value) => values.push(value),
                        None => return Err(A::Error::invalid_length(values.len(), &self)),
                    }
                }
                let mut length = N;
                while seq.next_element::<IgnoredAny>()?.is_some() {
                    length += 1;
                }
                if length != N {
                    return Err(A::Error::invalid_length(length, &self));
                }
                let values: [T; N] = values.try_into().unwrap_or_else(|_| unreachable!());
                Ok(Exact(values))
            }
        }
        deserializer.deserialize_seq(Values(PhantomData))
    }
}

/// A field `[T; N]` (`#[serde(deserialize_with = "exact")]`).
pub(crate) fn exact<'de, D, T, const N: usize>(deserializer: D) -> Result<[T; N], D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Exact::deserialize(deserializer).map(|exact| exact.0)
}

/// A field `Option<[T; N]>` (with `default`: absent is `None`).
pub(crate) fn exact_opt<'de, D, T, const N: usize>(
    deserializer: D,
) -> Result<Option<[T; N]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    Option::<Exact<T, N>>::deserialize(deserializer).map(|exact| exact.map(|e| e.0))
}

/// A field `Option<[[T; N]; M]>`: each row exactly N long too.
pub(crate) fn exact_rows_opt<'de, D, T, const N: usize, const M: usize>(
    deserializer: D,
) -> Result<Option<[[T; N]; M]>, D::Error>
where
    D: Deserializer<'de>,
    T: Deserialize<'de>,
{
    let rows = Option::<Exact<Exact<T, N>, M>>::deserialize(deserializer)?;
    Ok(rows.map(|rows| rows.0.map(|row| row.0)))
}
