//! A per-thread memo of the shadow's knob deltas (speed only; issue 10, "Speed").
//!
//! A least-squares Jacobian by forward differences moves one parameter at a time, so between two
//! calls of [`super::ShadowSimulation`]'s `simulate` most knobs of most tests sit at the same
//! coordinate. The memo keeps, per thread, the last coordinate and delta of every (test, knob) of
//! the last shadow simulated on that thread, and hands the delta back when the coordinate repeats
//! bit for bit. A knob delta is a pure function of the shadow's immutable tables and the
//! coordinate, so a hit returns exactly what the spline would: the results are bit-identical with
//! or without the memo, whichever threads run which fits.

use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::spline::{Table, WIDTH};

/// Source of shadow identities: each tabulated shadow takes the next (never 0).
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

/// A fresh identity for a newly tabulated shadow.
pub(super) fn next_id() -> u64 {
    NEXT_ID.fetch_add(1, Ordering::Relaxed)
}

/// The memo of one thread: the shadow it holds deltas of, and per slot (test x knob) the last
/// coordinate's bits and its delta.
#[derive(Default)]
pub(super) struct Memo {
    shadow: u64,
    slots: Vec<Option<(u64, [f64; WIDTH])>>,
}

impl Memo {
    /// `table.delta(u)`, from the memo when slot `slot` last saw the same `u`.
    pub(super) fn delta(&mut self, slot: usize, table: &Table, u: f64) -> [f64; WIDTH] {
        let bits = u.to_bits();
        match self.slots[slot] {
            Some((b, d)) if b == bits => d,
            _ => {
                let d = table.delta(u);
                self.slots[slot] = Some((bits, d));
                d
            }
        }
    }
}

thread_local! {
    static MEMO: RefCell<Memo> = RefCell::new(Memo::default());
}

/// Runs `f` with this thread's memo, emptied first unless it holds shadow `shadow` with `slots`
/// slots.
pub(super) fn with_memo<R>(shadow: u64, slots: usize, f: impl FnOnce(&mut Memo) -> R) -> R {
    MEMO.with(|cell| {
        let mut memo = cell.borrow_mut();
        if memo.shadow != shadow || memo.slots.len() != slots {
            memo.shadow = shadow;
            memo.slots.clear();
            memo.slots.resize(slots, None);
        }
        f(&mut memo)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> Table {
        let u = [0.0, 0.5, 1.0, 1.5, 2.0];
        let v: Vec<Option<[f64; WIDTH]>> = u.iter().map(|x: &f64| Some([x.exp(), x * x, 0.0, 0.0, 0.0])).collect();
        Table::new(&u, &v, 1.0).expect("off is a solved node")
    }

    #[test]
    fn a_hit_returns_exactly_what_the_table_gives() {
        let t = table();
        let id = next_id();
        for u in [0.3, 0.3, 1.7, 0.3, 1.0, 1.7] {
            let got = with_memo(id, 2, |m| m.delta(1, &t, u));
            assert_eq!(got, t.delta(u), "u = {u}");
        }
    }

    #[test]
    fn another_shadow_or_slot_never_sees_a_stale_delta() {
        let (t, id_a, id_b) = (table(), next_id(), next_id());
        let first = with_memo(id_a, 2, |m| m.delta(0, &t, 0.3));
        // Same slot and coordinate under another shadow whose table differs: computed afresh.
        let other = Table::new(&[0.0, 1.0, 2.0], &[Some([0.0; WIDTH]), Some([1.0; WIDTH]), Some([5.0; WIDTH])], 1.0)
            .expect("off is a solved node");
        let second = with_memo(id_b, 2, |m| m.delta(0, &other, 0.3));
        assert_eq!(first, t.delta(0.3));
        assert_eq!(second, other.delta(0.3));
        assert_ne!(first, second);
    }
}
