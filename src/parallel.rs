//! Independent work on all cores, on rayon's work-stealing pool. Kernels stay single-threaded
//! (on the 2-core target machine 2-thread dense kernels were slower than 1); what runs
//! concurrently is whole, independent pieces of the pipeline (candidates, maps, ranges of
//! vertices), and results never depend on the number of cores: every primitive returns the
//! serial result, in order.
//!
//! Why a pool: the maps stage has hundreds of parallel regions of 0.1–3 ms. Spawning scoped
//! threads for each cost about 80 µs per region on the 2-core VM (a spawn and a futex wake-up
//! of the other virtual CPU), and nested regions (a vertex loop inside a candidate's map,
//! itself one of several on all cores) cost next to nothing when the cores are busy: the inner
//! work just runs where it is.
//!
//! Waking a pool thread that went to sleep is another matter on a VM: its virtual CPU is
//! parked, and the hypervisor takes 0.3–4 ms to run it again, longer than most regions. So
//! [`detect`](crate::detect()) runs the pipeline *on* a pool thread ([`on_pool`]: a region
//! starts on the thread that enters it instead of waiting for a sleeping one to take it) and
//! keeps the other pool threads spinning meanwhile ([`spinner`]). Both change when work runs,
//! never what it computes.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;

/// The number of cores, asked once: `available_parallelism` reads the cgroup's quota files
/// on every call (about ten system calls).
pub(crate) fn cores() -> usize {
    static CORES: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |t| t.get()))
}

/// `f` applied to every item, results in item order. Items are handed out one at a time (their
/// costs vary: a candidate's profile map, a symmetry's polish), so no core idles while work
/// remains.
pub(crate) fn map<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> R + Sync + Send) -> Vec<R> {
    if cores() <= 1 || items.len() <= 1 {
        return items.iter().map(f).collect();
    }
    items.par_iter().with_max_len(1).map(f).collect()
}

/// `f(range)` over `0..len` cut into one contiguous range per core, results in range order: for
/// loops over vertices whose items are independent and cheap (a range amortises the hand-off).
pub(crate) fn chunks<R: Send>(len: usize, f: impl Fn(std::ops::Range<usize>) -> R + Sync + Send) -> Vec<R> {
    // Below this many items per range a loop is not worth splitting.
    const MIN_CHUNK: usize = 256;
    let parts = cores().min(len.div_ceil(MIN_CHUNK)).max(1);
    if parts <= 1 {
        return vec![f(0..len)];
    }
    let size = len.div_ceil(parts);
    let ranges: Vec<std::ops::Range<usize>> = (0..len).step_by(size).map(|a| a..(a + size).min(len)).collect();
    map(&ranges, |r| f(r.clone()))
}

/// `(a(), b())`, possibly on two cores; a panic in either is re-raised here.
pub(crate) fn join<A: Send, B: Send>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B + Send) -> (A, B) {
    if cores() <= 1 {
        return (a(), b());
    }
    rayon::join(a, b)
}

/// `work(relay)` on a thread of the pool, with `progress` called on this thread: each
/// `relay(fraction)` inside `work` hands the fraction over, waits, and returns what
/// `progress` answered here. Returns `work`'s result (a panic in `work` is re-raised here).
///
/// Why: a parallel region entered from a thread outside the pool queues its work and puts
/// that thread to sleep until a pool thread, possibly asleep itself, wakes and takes it; on the
/// 2-core VM waking a parked virtual CPU takes 0.3–4 ms, and the maps stage enters hundreds of
/// regions. From a pool thread the region's first half runs at once where it is, and the
/// other core joins when it is awake (the whole detection 6–9% faster at 5k). While `work`
/// runs, the pool's other threads stay awake ([`spinner`]; 0–5% more). Callers already on a
/// pool thread, and machines with one core, run `work` directly.
pub(crate) fn on_pool<R: Send>(progress: &mut dyn FnMut(f64) -> bool, work: impl FnOnce(&mut dyn FnMut(f64) -> bool) -> R + Send) -> R {
    if cores() <= 1 || rayon::current_thread_index().is_some() {
        return work(progress);
    }
    enum Message<R> {
        Progress(f64),
        Done(R),
    }
    let (to_caller, from_work) = std::sync::mpsc::channel::<Message<R>>();
    let (to_work, answers) = std::sync::mpsc::channel::<bool>();
    let result = rayon::in_place_scope(|scope| {
        scope.spawn(move |_| {
            let stop = AtomicBool::new(false);
            let result = rayon::in_place_scope(|inner| {
                // This thread runs the pipeline (no spinner here), and the spinners stop when
                // `work` ends, by a panic too (the scope waits for them).
                let _pipeline = Pipeline::enter();
                let _stop = Raised(&stop);
                if spin_wanted() {
                    // One spinner per pool thread (this one's ends at once).
                    let stop = &stop;
                    inner.spawn_broadcast(move |s, _| spinner(s, stop));
                }
                let mut relay = |f: f64| to_caller.send(Message::Progress(f)).is_ok() && answers.recv().unwrap_or(false);
                work(&mut relay)
            });
            // The receiver lives until this message arrives.
            let _ = to_caller.send(Message::Done(result));
        });
        loop {
            match from_work.recv() {
                Ok(Message::Progress(f)) => {
                    // The worker waits for this answer (it is gone only after a panic).
                    let _ = to_work.send(progress(f));
                }
                Ok(Message::Done(result)) => return Some(result),
                // `work` panicked: the scope re-raises its panic when it ends.
                Err(_) => return None,
            }
        }
    });
    result.expect("a worker that ends without a result has panicked, and the scope re-raised it")
}

/// Most pool threads kept spinning by [`on_pool`]: on a larger machine a sleeping thread wakes
/// fast enough, and burning many cores would be rude.
const MAX_SPINNING: usize = 8;

/// Whether [`on_pool`] keeps the pool's other threads spinning: with at most [`MAX_SPINNING`]
/// threads, unless the environment variable `INTRINSYM_SPIN` is `0`.
fn spin_wanted() -> bool {
    static WANTED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *WANTED.get_or_init(|| rayon::current_num_threads() <= MAX_SPINNING && std::env::var("INTRINSYM_SPIN").map_or(true, |v| v != "0"))
}

thread_local! {
    /// Whether this thread is running a [`spinner`] already.
    static SPINNING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// Whether this thread is running the work of an [`on_pool`].
    static PIPELINE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// How long a [`spinner`] spins before it hands itself back to its thread's queue.
const SPIN_TURN: std::time::Duration = std::time::Duration::from_micros(100);

/// Keeps a pool thread awake until `stop`: it takes every job the moment one is queued
/// (`rayon::yield_now`) and spins in between, so the parallel regions of the pipeline (most
/// of 0.1–3 ms) find a core that is running instead of a parked virtual CPU to wake (0.3–4 ms
/// on the 2-core VM). The results do not change: jobs run where they would, only sooner.
///
/// Deadlock-free by construction:
/// - a spinner spins for one [`SPIN_TURN`] at most, then queues itself again on its thread
///   and returns. A thread may take a spinner while it waits inside some job `J` (rayon runs
///   other jobs while a join waits); spinning there until the pipeline ends could wait for
///   `J`, that is for itself. After a turn `J` continues;
/// - a spinner never runs on a thread that runs a pipeline ([`PIPELINE`]: it would delay it)
///   nor inside another spinner ([`SPINNING`]): it ends at once there.
fn spinner<'s>(scope: &rayon::Scope<'s>, stop: &'s AtomicBool) {
    if stop.load(Ordering::Relaxed) || SPINNING.get() || PIPELINE.get() {
        return;
    }
    SPINNING.set(true);
    let end = std::time::Instant::now() + SPIN_TURN;
    let mut round = 0u32;
    while !stop.load(Ordering::Relaxed) {
        if rayon::yield_now() != Some(rayon::Yield::Executed) {
            std::hint::spin_loop();
        }
        round = round.wrapping_add(1);
        if round % 64 == 0 && std::time::Instant::now() >= end {
            break;
        }
    }
    SPINNING.set(false);
    if !stop.load(Ordering::Relaxed) {
        scope.spawn(move |s| spinner(s, stop));
    }
}

/// Marks this thread as running a pipeline ([`PIPELINE`]) until dropped.
struct Pipeline(bool);

impl Pipeline {
    fn enter() -> Pipeline {
        Pipeline(PIPELINE.replace(true))
    }
}

impl Drop for Pipeline {
    fn drop(&mut self) {
        PIPELINE.set(self.0);
    }
}

/// Raises its flag when dropped.
struct Raised<'a>(&'a AtomicBool);

impl Drop for Raised<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

/// Whether more than one core is available (speculative work is pointless otherwise).
pub(crate) fn available() -> bool {
    cores() > 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Results are in order whatever the threads, nested calls included.
    #[test]
    fn map_chunks_and_join_give_the_serial_results() {
        let items: Vec<usize> = (0..1000).collect();
        let serial: Vec<usize> = items.iter().map(|x| x * x).collect();
        assert_eq!(map(&items, |x| x * x), serial);
        let inner = map(&[0usize, 1], |&k| chunks(1000, |r| r.map(|x| x * x + k).sum::<usize>()).into_iter().sum::<usize>());
        let total: usize = serial.iter().sum();
        assert_eq!(inner, vec![total, total + 1000]);
        let parts = chunks(1000, |r| r.map(|x| x * x).collect::<Vec<_>>());
        assert_eq!(parts.concat(), serial);
        assert_eq!(chunks(0, |r| r.len()), vec![0]);
        let (a, b) = join(|| map(&items, |x| x + 1), || chunks(10, |r| r.len()));
        assert_eq!(a.len(), 1000);
        assert_eq!(b.iter().sum::<usize>(), 10);
    }

    /// `on_pool`: the work's progress reaches the caller's thread in order, its answers reach
    /// the work, the work's parallel regions give the serial results (spinners running), and a
    /// call from inside the pool runs in place.
    #[test]
    fn on_pool_relays_progress_to_the_calling_thread() {
        let caller = std::thread::current().id();
        let mut seen = Vec::new();
        let mut progress = |f: f64| {
            assert_eq!(std::thread::current().id(), caller);
            seen.push(f);
            f < 0.5
        };
        let items: Vec<usize> = (0..5000).collect();
        let (answers, sum, nested) = on_pool(&mut progress, |relay| {
            let answers: Vec<bool> = (0..4).map(|i| relay(i as f64 / 4.0)).collect();
            let sum: usize = map(&items, |&x| chunks(100, |r| r.map(|y| x ^ y).sum::<usize>()).into_iter().sum::<usize>()).into_iter().sum();
            let nested = on_pool(&mut |_| true, |_| join(|| 1, || 2));
            (answers, sum, nested)
        });
        assert_eq!(seen, vec![0.0, 0.25, 0.5, 0.75]);
        assert_eq!(answers, vec![true, true, false, false]);
        let serial: usize = items.iter().map(|&x| (0..100).map(|y| x ^ y).sum::<usize>()).sum();
        assert_eq!(sum, serial);
        assert_eq!(nested, (1, 2));
    }

    /// Pipelines started from several threads at once share the pool and all finish (a
    /// spinner must never wait for a job below it on its own thread), with the serial results.
    #[test]
    fn concurrent_pipelines_finish() {
        let items: Vec<usize> = (0..2000).collect();
        let serial: usize = items.iter().map(|&x| (0..300).map(|y| x ^ y).sum::<usize>()).sum();
        let run = || {
            on_pool(&mut |_| true, |relay| {
                let mut total = 0;
                for round in 0..20 {
                    relay(round as f64 / 20.0);
                    total = map(&items, |&x| chunks(300, |r| r.map(|y| x ^ y).sum::<usize>()).into_iter().sum::<usize>()).into_iter().sum::<usize>();
                    let (a, b) = join(|| chunks(1000, |r| r.len()), || map(&[1usize, 2], |x| x + 1));
                    assert_eq!((a.iter().sum::<usize>(), b), (1000, vec![2, 3]));
                }
                total
            })
        };
        std::thread::scope(|scope| {
            let threads: Vec<_> = (0..3).map(|_| scope.spawn(run)).collect();
            for t in threads {
                assert_eq!(t.join().expect("a pipeline thread"), serial);
            }
        });
    }

    /// A panic in the work reaches the caller (and the spinners stop: the call returns).
    #[test]
    fn on_pool_reraises_a_panic_of_the_work() {
        let caught = std::panic::catch_unwind(|| on_pool(&mut |_| true, |relay| -> usize {
            relay(0.1);
            panic!("inside the pool")
        }));
        let message = caught.expect_err("the panic is re-raised");
        assert_eq!(message.downcast_ref::<&str>(), Some(&"inside the pool"));
        // The pool still works.
        assert_eq!(on_pool(&mut |_| true, |_| map(&[1, 2, 3], |x| x * 2)), vec![2, 4, 6]);
    }
}
