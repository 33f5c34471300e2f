//! Embree backend (being written).
#![allow(unsafe_code)]
