//! Embree backend.
#![allow(unsafe_code)]

mod ffi;
