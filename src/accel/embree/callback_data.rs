//! `CallbackData<T>`: a value Embree reaches through a `void*` user pointer.

use std::ffi::c_void;
use std::ptr::NonNull;

/// A heap value with a stable address, freed on drop, handed to Embree as a user pointer.
///
/// Held as a raw pointer rather than a `Box` because Embree keeps its own copy of the
/// pointer while we own the value: moving a `Box` asserts unique access, which would
/// invalidate Embree's copy under Rust's aliasing rules. Shared access only: Embree's
/// callbacks and Rust both take `&T` (use interior mutability, e.g. a `Mutex`, to write).
pub struct CallbackData<T: Send + Sync + 'static> {
    ptr: NonNull<T>,
}

// SAFETY: `CallbackData<T>` owns a `T` and gives out only `&T`, so it is as thread-safe as
// `T`, which the bounds require to be `Send + Sync`.
unsafe impl<T: Send + Sync + 'static> Send for CallbackData<T> {}
// SAFETY: as above.
unsafe impl<T: Send + Sync + 'static> Sync for CallbackData<T> {}

impl<T: Send + Sync + 'static> CallbackData<T> {
    pub fn new(value: T) -> Self {
        CallbackData { ptr: NonNull::from(Box::leak(Box::new(value))) }
    }

    pub fn get(&self) -> &T {
        // SAFETY: `ptr` came from `Box::leak` and is freed only in `drop`; only shared
        // references to the value are ever created.
        unsafe { self.ptr.as_ref() }
    }

    /// The pointer to give Embree; valid until `self` is dropped.
    pub fn user_ptr(&self) -> *mut c_void {
        self.ptr.as_ptr().cast()
    }
}

impl<T: Send + Sync + 'static> Drop for CallbackData<T> {
    fn drop(&mut self) {
        // SAFETY: `ptr` came from `Box::leak` in `new` and is freed exactly once, here. Owners
        // drop this only after Embree can no longer call back with it (documented where
        // each `CallbackData` is kept).
        drop(unsafe { Box::from_raw(self.ptr.as_ptr()) });
    }
}
