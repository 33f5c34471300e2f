//! `Device`: one Embree device and the log its error callback writes to.

use super::callback_data::CallbackData;
use super::ffi;
use crate::accel::AccelError;
use std::ffi::{CStr, CString, c_char, c_void};
use std::sync::Mutex;
use std::sync::atomic::{AtomicIsize, Ordering};

/// Errors Embree reported through the callback since the last [`Device::check`].
///
/// Shared (not thread-local) because Embree may report from its own worker threads, e.g.
/// while building a scene in parallel.
#[derive(Default)]
struct ErrorLog {
    reported: Mutex<Reported>,
}

/// The first message is kept because it is usually the cause (later ones tend to be
/// consequences); the rest are only counted so the log cannot grow without bound.
#[derive(Default)]
struct Reported {
    first: Option<String>,
    count: usize,
}

/// An Embree device. Scenes and geometries hold an `Arc<Device>` so it outlives them.
pub struct Device {
    handle: ffi::RTCDevice,
    /// Embree keeps its address as the error callback's user pointer; dropped after the
    /// callback is unregistered (field drop runs after `Drop::drop`).
    log: CallbackData<ErrorLog>,
    /// Bytes Embree holds for this device (its BVHs, buffers and allocators), counted by
    /// its memory monitor callback; unregistered in `Drop` like the error callback.
    allocated: CallbackData<AtomicIsize>,
}

// SAFETY: Embree's API is thread-safe for a device (objects created from it may be used from
// any thread), and the only Rust state, `ErrorLog`, is behind a mutex.
unsafe impl Send for Device {}
// SAFETY: as above; `&Device` only exposes the handle and the mutex-protected log.
unsafe impl Sync for Device {}

impl Device {
    /// Creates a device with an Embree configuration string (e.g. `""`, `"threads=1"`).
    pub fn new(config: &str) -> Result<Device, AccelError> {
        let c_config = CString::new(config).map_err(|_| {
            AccelError::Embree(format!("device configuration {config:?} contains a NUL byte"))
        })?;
        // SAFETY: `c_config` is a NUL-terminated string that lives across the call.
        let handle = unsafe { ffi::rtcNewDevice(c_config.as_ptr()) };
        if handle.is_null() {
            // SAFETY: a null device asks for the error of the last failed device creation.
            let code = unsafe { ffi::rtcGetDeviceError(std::ptr::null_mut()) };
            return Err(AccelError::Embree(format!(
                "cannot create a device with configuration {config:?} ({code:?})"
            )));
        }
        let log = CallbackData::new(ErrorLog::default());
        // SAFETY: `handle` is a live device. The user pointer is owned by the returned
        // `Device`, which unregisters the callback before freeing it (see `Drop`).
        unsafe { ffi::rtcSetDeviceErrorFunction(handle, Some(on_error), log.user_ptr()) };
        let allocated = CallbackData::new(AtomicIsize::new(0));
        // SAFETY: as for the error callback: the counter outlives the registration.
        unsafe {
            ffi::rtcSetDeviceMemoryMonitorFunction(handle, Some(on_memory), allocated.user_ptr())
        };
        Ok(Device { handle, log, allocated })
    }

    pub fn handle(&self) -> ffi::RTCDevice {
        self.handle
    }

    /// `rtcGetDeviceProperty`: one of the device's read-only properties.
    pub fn property(&self, property: ffi::RTCDeviceProperty) -> isize {
        // SAFETY: `handle` is a live device and `property` one of the header's values;
        // Embree reports an unknown property through the error callback, not by UB.
        unsafe { ffi::rtcGetDeviceProperty(self.handle, property) }
    }

    /// Bytes Embree currently holds for this device, as its memory monitor reports them.
    pub fn allocated_bytes(&self) -> usize {
        self.allocated.get().load(Ordering::Relaxed).max(0) as usize
    }

    /// `Err` with Embree's messages if it reported any error since the last check.
    pub fn check(&self) -> Result<(), AccelError> {
        // SAFETY: `self.handle` is live. This also clears the calling thread's error code,
        // so a stale code cannot surface in a later check.
        let code = unsafe { ffi::rtcGetDeviceError(self.handle) };
        let reported = std::mem::take(&mut *lock(&self.log.get().reported));
        match (reported.first, code) {
            (None, ffi::RTCError::NONE) => Ok(()),
            (None, code) => Err(AccelError::Embree(format!("error {code:?}"))),
            (Some(first), _) if reported.count <= 1 => Err(AccelError::Embree(first)),
            (Some(first), _) => {
                Err(AccelError::Embree(format!("{first} (and {} more errors)", reported.count - 1)))
            }
        }
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        // SAFETY: `self.handle` is live. Unregistering first means that, should Embree keep
        // the device alive for a moment, it can never call back into the freed log.
        unsafe {
            ffi::rtcSetDeviceErrorFunction(self.handle, None, std::ptr::null_mut());
            ffi::rtcSetDeviceMemoryMonitorFunction(self.handle, None, std::ptr::null_mut());
            ffi::rtcReleaseDevice(self.handle);
        }
    }
}

fn lock(m: &Mutex<Reported>) -> std::sync::MutexGuard<'_, Reported> {
    // A poisoned log is still a valid log; never panic over it (this runs inside a callback).
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Embree's error callback. `extern "C"`: must not unwind, so nothing here can panic.
unsafe extern "C" fn on_error(user_ptr: *mut c_void, code: ffi::RTCError, message: *const c_char) {
    if user_ptr.is_null() {
        return;
    }
    // SAFETY: `user_ptr` was registered in `Device::new` and points to the device's
    // `ErrorLog`, which stays alive until the callback is unregistered in `Drop`; Embree
    // and Rust only take shared references to it.
    let log = unsafe { &*user_ptr.cast::<ErrorLog>() };
    let mut reported = lock(&log.reported);
    reported.count = reported.count.saturating_add(1);
    if reported.first.is_some() {
        return;
    }
    reported.first = Some(if message.is_null() {
        format!("error {code:?}")
    } else {
        // SAFETY: Embree passes a NUL-terminated string valid for the duration of the call.
        let msg = unsafe { CStr::from_ptr(message) }.to_string_lossy();
        format!("{msg} ({code:?})")
    });
}

/// Embree's memory monitor: `bytes` allocated (positive) or freed (negative). Embree's
/// documentation tracks usage by accumulating every call (an allocation that fails is
/// reported back with negative bytes); returning true lets the allocation go ahead.
/// `extern "C"`: nothing here can panic.
unsafe extern "C" fn on_memory(user_ptr: *mut c_void, bytes: isize, _post: bool) -> bool {
    if !user_ptr.is_null() {
        // SAFETY: `user_ptr` was registered in `Device::new` and points to the device's
        // counter, alive until the callback is unregistered in `Drop`.
        let counter = unsafe { &*user_ptr.cast::<AtomicIsize>() };
        counter.fetch_add(bytes, Ordering::Relaxed);
    }
    true
}
