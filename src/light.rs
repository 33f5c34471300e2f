//! Lights (stub, being written).
#[derive(Clone, Debug, Default)]
pub struct LightSet {}
