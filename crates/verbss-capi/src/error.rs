//! Status codes, the per-thread message of the last failure, and the guard
//! that turns an error or a panic into both.

use std::cell::RefCell;
use std::ffi::{c_char, c_int, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use verbss::Error;

/// Success.
pub const VERBSS_OK: c_int = 0;
/// Bad input: a NULL pointer, an array of the wrong length, an invalid mesh,
/// setting or displacement. Nothing changed.
pub const VERBSS_ERROR_INPUT: c_int = 2;
/// The step inverted an element: it was rejected, the deformer keeps the last
/// accepted step (the same codes as the `verbss` command).
pub const VERBSS_ERROR_INVERTED: c_int = 3;
/// A bug in verbss, caught before it reached the caller.
pub const VERBSS_ERROR_INTERNAL: c_int = 4;

/// An error and the status it returns.
pub(crate) struct Failure {
    code: c_int,
    message: String,
}

impl From<Error> for Failure {
    fn from(e: Error) -> Failure {
        let code = match e {
            Error::Inverted { .. } => VERBSS_ERROR_INVERTED,
            _ => VERBSS_ERROR_INPUT,
        };
        Failure {
            code,
            message: e.to_string(),
        }
    }
}

/// Bad input, with `message` as it is.
pub(crate) fn input(message: String) -> Failure {
    Failure {
        code: VERBSS_ERROR_INPUT,
        message,
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(message: &str) {
    let text = CString::new(message.replace('\0', "")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = text);
}

/// Runs `body`, turning its error or panic into a status and the thread's
/// last error message.
pub(crate) fn guard(body: impl FnOnce() -> Result<(), Failure>) -> c_int {
    let failure = match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => return VERBSS_OK,
        Ok(Err(failure)) => failure,
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Failure {
                code: VERBSS_ERROR_INTERNAL,
                message: format!("internal error: {what}"),
            }
        }
    };
    set_last_error(&failure.message);
    failure.code
}

/// The `len` elements at `ptr`, or an error naming `what` when `ptr` is NULL
/// (an empty array may be NULL).
///
/// # Safety
/// A non-NULL `ptr` must point to `len` readable elements.
pub(crate) unsafe fn slice<'a, T>(
    ptr: *const T,
    len: usize,
    what: &str,
) -> Result<&'a [T], Failure> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(input(format!("`{what}` is NULL")));
    }
    // SAFETY: the caller guarantees `len` readable elements at `ptr`.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// The UTF-8 text of the NUL-terminated string at `ptr`, or an error naming
/// `what`.
///
/// # Safety
/// A non-NULL `ptr` must point to a NUL-terminated string.
pub(crate) unsafe fn text<'a>(ptr: *const c_char, what: &str) -> Result<&'a str, Failure> {
    if ptr.is_null() {
        return Err(input(format!("`{what}` is NULL")));
    }
    // SAFETY: the caller guarantees a NUL-terminated string.
    unsafe { CStr::from_ptr(ptr) }
        .to_str()
        .map_err(|_| input(format!("`{what}` is not UTF-8 text")))
}

/// The message of the last call that failed on this thread ("" if none):
/// the text the `verbss` command prints after `error: `. The pointer stays
/// valid until the next failing call on this thread.
#[no_mangle]
pub extern "C" fn verbss_last_error() -> *const c_char {
    catch_unwind(|| LAST_ERROR.with(|e| e.borrow().as_ptr())).unwrap_or(c"".as_ptr())
}
