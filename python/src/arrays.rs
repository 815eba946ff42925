//! # Arrays at the boundary
//!
//! numpy in (any array-like: converted to contiguous float64 only when it is not one already)
//! and numpy out (owned buffers handed to numpy without a copy), with the shape checks and
//! messages every method shares.

use crate::value_error;
use numpy::ndarray::{ArrayD, IxDyn};
use numpy::{
    IntoPyArray, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyReadwriteArrayDyn,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyDict;
use std::borrow::Cow;

/// Arrays up to this many elements are copied at once (cheaper than registering a borrow).
const COPY_BELOW: usize = 4096;

/// A float64 array from Python: borrowed (large arrays: read later with the GIL released) or
/// copied (small ones, or lists and other dtypes converted with `numpy.asarray`).
pub enum FloatArray<'py> {
    Borrowed(PyReadonlyArrayDyn<'py, f64>),
    Owned { shape: Vec<usize>, data: Vec<f64> },
}

static AS_FLOAT: PyOnceLock<Py<PyAny>> = PyOnceLock::new();

impl<'py> FloatArray<'py> {
    /// Reads `obj` if it is an aligned C-contiguous float64 ndarray, else converts it with
    /// `numpy.require`.
    pub fn new(obj: &Bound<'py, PyAny>, what: &str) -> PyResult<Self> {
        if let Ok(array) = obj.cast::<PyArrayDyn<f64>>() {
            if array.len() <= COPY_BELOW {
                // SAFETY: the GIL is held and no Python code runs during the copy, so nothing
                // writes to the array meanwhile; the slice does not outlive this statement.
                // `as_slice` checks contiguity and alignment.
                if let Ok(s) = unsafe { array.as_slice() } {
                    return Ok(Self::Owned {
                        shape: array.shape().to_vec(),
                        data: s.to_vec(),
                    });
                }
            } else if let Ok(ro) = array.try_readonly()
                && ro.as_slice().is_ok()
            {
                return Ok(Self::Borrowed(ro));
            }
        }
        let py = obj.py();
        // Lists, other dtypes, strided or misaligned arrays (as unpickled buffers can be): an
        // aligned C-contiguous float64 copy.
        let require = AS_FLOAT.get_or_try_init(py, || -> PyResult<Py<PyAny>> {
            Ok(py.import("numpy")?.getattr("require")?.unbind())
        })?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("dtype", "float64")?;
        kwargs.set_item("requirements", "CA")?;
        let converted = require
            .bind(py)
            .call((obj,), Some(&kwargs))
            .map_err(|e| value_error(format!("{what}: not an array of numbers ({e})")))?;
        let array = converted
            .extract::<PyReadonlyArrayDyn<'py, f64>>()
            .map_err(|e| value_error(format!("{what}: {e}")))?;
        let data = array
            .as_slice()
            .map_err(|e| value_error(format!("{what}: {e}")))?
            .to_vec();
        Ok(Self::Owned {
            shape: array.shape().to_vec(),
            data,
        })
    }

    /// The shape.
    pub fn shape(&self) -> &[usize] {
        match self {
            Self::Borrowed(a) => a.shape(),
            Self::Owned { shape, .. } => shape,
        }
    }

    /// The elements in C order (borrowed when possible).
    pub fn data(&self) -> Cow<'_, [f64]> {
        match self {
            Self::Borrowed(a) => match a.as_slice() {
                Ok(s) => Cow::Borrowed(s),
                Err(_) => Cow::Owned(a.as_array().iter().copied().collect()),
            },
            Self::Owned { data, .. } => Cow::Borrowed(data),
        }
    }

    /// Errors unless every element is finite.
    pub fn check_finite(&self, what: &str) -> PyResult<()> {
        let data = self.data();
        match data.iter().position(|v| !v.is_finite()) {
            Some(k) => Err(value_error(format!(
                "{what}: element {} is {} (every value must be finite)",
                unravel(self.shape(), k),
                data[k]
            ))),
            None => Ok(()),
        }
    }
}

/// `[i, j, …]` of the flat C-order index `k` in `shape`.
fn unravel(shape: &[usize], mut k: usize) -> String {
    let mut idx = vec![0; shape.len()];
    for (d, &n) in shape.iter().enumerate().rev() {
        if n > 0 {
            idx[d] = k % n;
            k /= n;
        }
    }
    format!("{idx:?}")
}

/// Rows of `width` numbers: `(N, width)` (a batch) or `(width,)` (one row, `single`).
pub struct Rows<'py> {
    pub array: FloatArray<'py>,
    pub count: usize,
    pub single: bool,
}

impl<'py> Rows<'py> {
    /// Reads `obj` as rows of `width`, checking shape and finiteness; `hint` says what a row is.
    pub fn new(obj: &Bound<'py, PyAny>, width: usize, what: &str, hint: &str) -> PyResult<Self> {
        let array = FloatArray::new(obj, what)?;
        let (count, single) = match array.shape() {
            [w] if *w == width => (1, true),
            [n, w] if *w == width => (*n, false),
            s => {
                return Err(value_error(format!(
                    "{what}: expected shape (N, {width}) or ({width},) ({hint}), got {}",
                    shape_string(s)
                )));
            }
        };
        array.check_finite(what)?;
        Ok(Self {
            array,
            count,
            single,
        })
    }
}

/// `(a, b)` as Python prints a shape.
pub fn shape_string(s: &[usize]) -> String {
    match s {
        [a] => format!("({a},)"),
        _ => format!(
            "({})",
            s.iter()
                .map(|v| v.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A numpy array of `shape` owning `data` (C order), without a copy.
pub fn to_numpy<'py, T: numpy::Element>(
    py: Python<'py>,
    shape: &[usize],
    data: Vec<T>,
) -> Bound<'py, PyArrayDyn<T>> {
    ArrayD::from_shape_vec(IxDyn(shape), data)
        .expect("buffer length matches the shape")
        .into_pyarray(py)
}

/// A new zero-filled float64 numpy array of `shape`.
pub fn zeros<'py>(py: Python<'py>, shape: &[usize]) -> Bound<'py, PyArrayDyn<f64>> {
    PyArrayDyn::zeros(py, IxDyn(shape), false)
}

/// The elements of arrays made by [`zeros`], writable (they are not shared with Python yet).
pub fn writable<'a>(arrays: &'a mut [Bound<'_, PyArrayDyn<f64>>]) -> Vec<&'a mut [f64]> {
    arrays
        .iter_mut()
        // SAFETY: the arrays were just created by `zeros` (C-contiguous, no other reference:
        // Python has not seen them), and each is borrowed mutably once.
        .map(|a| unsafe { a.as_slice_mut() }.expect("a new array is contiguous"))
        .collect()
}

/// `shape` with the leading batch axis of length `count`, dropped for a single row.
pub fn batch_shape(single: bool, count: usize, rest: &[usize]) -> Vec<usize> {
    let mut s = Vec::with_capacity(rest.len() + 1);
    if !single {
        s.push(count);
    }
    s.extend_from_slice(rest);
    s
}

/// An output array the caller passed (`out=`), borrowed for writing: float64, C-contiguous,
/// writable, exactly `shape`, and not overlapping an array this call reads (numpy's borrow
/// checker refuses a write borrow of memory that is borrowed for reading).
pub fn out_array<'py>(
    array: &Bound<'py, PyArrayDyn<f64>>,
    shape: &[usize],
    what: &str,
) -> PyResult<PyReadwriteArrayDyn<'py, f64>> {
    if array.shape() != shape {
        return Err(value_error(format!(
            "out.{what}: expected shape {}, got {}",
            shape_string(shape),
            shape_string(array.shape())
        )));
    }
    let rw = array.try_readwrite().map_err(|e| {
        value_error(format!(
            "out.{what}: not writable, or it shares memory with an input ({e})"
        ))
    })?;
    if rw.as_slice().is_err() {
        return Err(value_error(format!("out.{what}: must be C-contiguous")));
    }
    Ok(rw)
}
