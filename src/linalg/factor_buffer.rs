//! Buffers kept between sparse factorizations (ours; docs/method.md section 20, "Large
//! meshes"): a large buffer written for the first time can cost more than the factorization
//! on a virtual machine (every fresh page faults through to the host). The value buffer of the
//! largest factorization is handed from one solver to the next (the parameterization factors
//! such systems one after another: the flattening's, then the transport's;
//! [`super::SpdSolver`] takes and leaves it, the parameterization frees it), and each solver
//! keeps its factorization work space ([`Scratch`]).

use std::mem::MaybeUninit;

/// Factor entries from which a factorization's value buffer is kept for the next one when its
/// solver is dropped ([`release_spare`]).
const SPARE_ENTRIES: usize = 1 << 24;

/// The value buffer of the largest factorization whose solver was dropped (see
/// [`take_spare`]).
static SPARE: std::sync::Mutex<Vec<f64>> = std::sync::Mutex::new(Vec::new());

/// Give `values` a capacity of at least `need` entries: the spare buffer when it is large
/// enough, else a new one with a quarter more room for the next pattern's fill (capacity that
/// is never written costs no memory).
pub(super) fn take_spare(values: &mut Vec<f64>, need: usize) {
    if values.capacity() >= need || need < SPARE_ENTRIES {
        return;
    }
    if let Ok(mut spare) = SPARE.lock() {
        if spare.capacity() >= need {
            *values = std::mem::take(&mut *spare);
            return;
        }
    }
    *values = Vec::with_capacity(need + need / 4);
}

/// Keep `values` as the spare buffer when it is large and larger than the spare.
pub(super) fn offer_spare(values: &mut Vec<f64>) {
    if values.capacity() < SPARE_ENTRIES {
        return;
    }
    if let Ok(mut spare) = SPARE.lock() {
        if spare.capacity() < values.capacity() {
            *spare = std::mem::take(values);
        }
    }
}

/// Free the spare factor buffer (the parameterization calls this when its last large
/// factorization is done, so that later stages do not carry it).
pub fn release_spare() {
    if let Ok(mut spare) = SPARE.lock() {
        *spare = Vec::new();
    }
}

/// The numeric factorization's work space, kept between factorizations: on the 776k brain it
/// is about 90 MB a factorization, above glibc's largest threshold for reusing freed memory,
/// so each factorization wrote fresh pages. Clones start empty.
#[derive(Default)]
pub(super) struct Scratch(Vec<MaybeUninit<u8>>);

impl Clone for Scratch {
    fn clone(&self) -> Self {
        Self::default()
    }
}

impl Scratch {
    /// At least `bytes` bytes of work space (an error when they cannot be allocated).
    pub(super) fn at_least(&mut self, bytes: usize) -> Result<&mut [MaybeUninit<u8>], std::collections::TryReserveError> {
        if self.0.len() < bytes {
            self.0 = Vec::new();
            self.0.try_reserve_exact(bytes)?;
            self.0.resize_with(bytes, MaybeUninit::uninit);
        }
        Ok(&mut self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_large_factor_buffer_is_handed_to_the_next_factorization() {
        // Capacity only: no page of these buffers is written.
        let mut dropped: Vec<f64> = Vec::with_capacity(SPARE_ENTRIES + 100);
        let address = dropped.as_ptr();
        offer_spare(&mut dropped);
        assert_eq!(dropped.capacity(), 0, "the buffer went to the spare");
        let mut next = Vec::new();
        take_spare(&mut next, SPARE_ENTRIES + 50);
        assert_eq!(next.as_ptr(), address, "the next large factorization takes it");
        // Too large for the spare: a new buffer with a quarter more room.
        offer_spare(&mut next);
        let mut larger = Vec::new();
        take_spare(&mut larger, SPARE_ENTRIES + 200);
        assert!(larger.capacity() >= (SPARE_ENTRIES + 200) * 5 / 4 && larger.as_ptr() != address);
        release_spare();
        assert_eq!(SPARE.lock().unwrap().capacity(), 0);
        // Small systems neither take nor leave one.
        let mut small = vec![0.0; 10];
        offer_spare(&mut small);
        assert_eq!(small.len(), 10);
    }
}
