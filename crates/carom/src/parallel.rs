//! Work shared among rayon's threads, only when there is enough of it. A fork costs
//! microseconds (more from a thread outside the pool, which must wake a worker and wait), so
//! small worlds run these loops on the calling thread and pay nothing; large ones split them
//! into tasks of at least `per_task` items. The results are the same either way: every item is
//! computed alone.

use rayon::prelude::*;
use std::ops::AddAssign;

/// True when `items` are worth splitting into tasks of `per_task`.
pub(crate) fn worth_sharing(items: usize, per_task: usize) -> bool {
    items >= 2 * per_task && rayon::current_num_threads() > 1
}

/// `out` becomes `f` of every item, in order (its memory reused).
pub(crate) fn map_into<T: Sync, U: Send>(
    items: &[T],
    out: &mut Vec<U>,
    per_task: usize,
    f: impl Fn(&T) -> U + Sync + Send,
) {
    if worth_sharing(items.len(), per_task) {
        items
            .par_iter()
            .with_min_len(per_task)
            .map(f)
            .collect_into_vec(out);
    } else {
        out.clear();
        out.extend(items.iter().map(f));
    }
}

/// `out` becomes `f` of every item and its index, in order (its memory reused).
pub(crate) fn map_indexed_into<T: Sync, U: Send>(
    items: &[T],
    out: &mut Vec<U>,
    per_task: usize,
    f: impl Fn(usize, &T) -> U + Sync + Send,
) {
    if worth_sharing(items.len(), per_task) {
        items
            .par_iter()
            .enumerate()
            .with_min_len(per_task)
            .map(|(i, item)| f(i, item))
            .collect_into_vec(out);
    } else {
        out.clear();
        out.extend(items.iter().enumerate().map(|(i, item)| f(i, item)));
    }
}

/// True when `test` holds for some item (on all threads when there are enough).
pub(crate) fn any<T: Sync>(
    items: &[T],
    per_task: usize,
    test: impl Fn(&T) -> bool + Sync + Send,
) -> bool {
    if worth_sharing(items.len(), per_task) {
        items.par_iter().with_min_len(per_task).any(test)
    } else {
        items.iter().any(test)
    }
}

/// `out` becomes `f` of every pair of `a[i]` and `b[i]`, in order (its memory reused).
pub(crate) fn map_zip_into<A: Sync, B: Sync, U: Send>(
    a: &[A],
    b: &[B],
    out: &mut Vec<U>,
    per_task: usize,
    f: impl Fn(&A, &B) -> U + Sync + Send,
) {
    if worth_sharing(a.len().min(b.len()), per_task) {
        a.par_iter()
            .zip(b.par_iter())
            .with_min_len(per_task)
            .map(|(a, b)| f(a, b))
            .collect_into_vec(out);
    } else {
        out.clear();
        out.extend(a.iter().zip(b).map(|(a, b)| f(a, b)));
    }
}

/// `out` becomes `f` of every pair of `a[i]` and `b[i]`, which `f` may change (`out`'s memory
/// reused).
pub(crate) fn map_zip_mut_into<A: Sync, B: Send, U: Send>(
    a: &[A],
    b: &mut [B],
    out: &mut Vec<U>,
    per_task: usize,
    f: impl Fn(&A, &mut B) -> U + Sync + Send,
) {
    if worth_sharing(a.len().min(b.len()), per_task) {
        a.par_iter()
            .zip(b.par_iter_mut())
            .with_min_len(per_task)
            .map(|(a, b)| f(a, b))
            .collect_into_vec(out);
    } else {
        out.clear();
        out.extend(a.iter().zip(b).map(|(a, b)| f(a, b)));
    }
}

/// `out` becomes `f` of every item, which `f` may change (`out`'s memory reused).
pub(crate) fn map_mut_into<T: Send, U: Send>(
    items: &mut [T],
    out: &mut Vec<U>,
    per_task: usize,
    f: impl Fn(&mut T) -> U + Sync + Send,
) {
    if worth_sharing(items.len(), per_task) {
        items
            .par_iter_mut()
            .with_min_len(per_task)
            .map(f)
            .collect_into_vec(out);
    } else {
        out.clear();
        out.extend(items.iter_mut().map(f));
    }
}

/// `f` on every item, which it may change.
pub(crate) fn for_each_mut<T: Send>(
    items: &mut [T],
    per_task: usize,
    f: impl Fn(&mut T) + Sync + Send,
) {
    if worth_sharing(items.len(), per_task) {
        items.par_iter_mut().with_min_len(per_task).for_each(f);
    } else {
        items.iter_mut().for_each(f);
    }
}

/// `f` on every pair of `inputs[i]` and `outputs[i]`.
pub(crate) fn for_each_with<A: Sync, B: Send>(
    inputs: &[A],
    outputs: &mut [B],
    per_task: usize,
    f: impl Fn(&A, &mut B) + Sync + Send,
) {
    if worth_sharing(outputs.len(), per_task) {
        inputs
            .par_iter()
            .zip(outputs.par_iter_mut())
            .with_min_len(per_task)
            .for_each(|(a, b)| f(a, b));
    } else {
        inputs
            .iter()
            .zip(outputs.iter_mut())
            .for_each(|(a, b)| f(a, b));
    }
}

/// `f` on runs of `inputs` and the same runs of `outputs` (of equal length), at least
/// `per_task` long when shared (on one thread, the whole of both at once).
pub(crate) fn for_each_chunk_with<A: Sync, B: Send>(
    inputs: &[A],
    outputs: &mut [B],
    per_task: usize,
    f: impl Fn(&[A], &mut [B]) + Sync + Send,
) {
    if worth_sharing(outputs.len(), per_task) {
        inputs
            .par_chunks(per_task)
            .zip(outputs.par_chunks_mut(per_task))
            .for_each(|(a, b)| f(a, b));
    } else {
        f(inputs, outputs);
    }
}

/// [`for_each_chunk_with`] where `f` may also change the inputs.
pub(crate) fn for_each_chunk_mut_with<A: Send, B: Send>(
    inputs: &mut [A],
    outputs: &mut [B],
    per_task: usize,
    f: impl Fn(&mut [A], &mut [B]) + Sync + Send,
) {
    if worth_sharing(outputs.len(), per_task) {
        inputs
            .par_chunks_mut(per_task)
            .zip(outputs.par_chunks_mut(per_task))
            .for_each(|(a, b)| f(a, b));
    } else {
        f(inputs, outputs);
    }
}

/// [`for_each_with`], adding up what `f` returns.
pub(crate) fn sum_with<A: Sync, B: Send, S: Default + AddAssign + Send>(
    inputs: &[A],
    outputs: &mut [B],
    per_task: usize,
    f: impl Fn(&A, &mut B) -> S + Sync + Send,
) -> S {
    let add = |mut total: S, part: S| {
        total += part;
        total
    };
    if worth_sharing(outputs.len(), per_task) {
        inputs
            .par_iter()
            .zip(outputs.par_iter_mut())
            .with_min_len(per_task)
            .map(|(a, b)| f(a, b))
            .reduce(S::default, add)
    } else {
        inputs
            .iter()
            .zip(outputs.iter_mut())
            .map(|(a, b)| f(a, b))
            .fold(S::default(), add)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_and_alone_give_the_same_results() {
        let inputs: Vec<u64> = (0..5000).collect();
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut squares = Vec::new();
                map_into(&inputs, &mut squares, 64, |x| x * x);
                assert_eq!(squares[4999], 4999 * 4999);
                let mut changed = inputs.clone();
                let mut halves = Vec::new();
                map_mut_into(&mut changed, &mut halves, 64, |x| {
                    *x += 1;
                    *x / 2
                });
                assert_eq!((changed[9], halves[9]), (10, 5));
                let mut sums = Vec::new();
                map_zip_into(&inputs, &squares, &mut sums, 64, |x, y| x + y);
                assert_eq!(sums[3], 3 + 9);
                let mut outputs = vec![0u64; 5000];
                for_each_with(&inputs, &mut outputs, 64, |x, out| *out = x + 1);
                assert!(outputs.iter().zip(&inputs).all(|(o, i)| *o == i + 1));
                let total = sum_with(&inputs, &mut outputs, 64, |x, _| *x);
                assert_eq!(total, 4999 * 5000 / 2);
                for_each_chunk_with(&inputs, &mut outputs, 64, |xs, outs| {
                    assert_eq!(xs.len(), outs.len());
                    for (x, out) in xs.iter().zip(outs) {
                        *out = 2 * x;
                    }
                });
                assert!(outputs.iter().zip(&inputs).all(|(o, i)| *o == 2 * i));
                let mut changed = inputs.clone();
                for_each_chunk_mut_with(&mut changed, &mut outputs, 64, |xs, outs| {
                    assert_eq!(xs.len(), outs.len());
                    for (x, out) in xs.iter_mut().zip(outs) {
                        *x += 1;
                        *out = 3 * *x;
                    }
                });
                assert!(changed.iter().zip(&inputs).all(|(c, i)| *c == i + 1));
                assert!(outputs.iter().zip(&inputs).all(|(o, i)| *o == 3 * (i + 1)));
            });
        }
    }
}
