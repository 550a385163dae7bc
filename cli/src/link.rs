//! The link to the terminal: how many frames may be on their way, and how
//! fast the terminal drains them (see the live loop's "Slow links").

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crate::terminal::probe::Capabilities;

/// Whether the terminal answers the status request sent after each frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Acks {
    /// Not known yet (no probe): the first request tells.
    Unknown,
    Yes,
    No,
}

/// A frame on its way to the terminal.
#[derive(Clone, Copy, Debug)]
struct Sent {
    start: Instant,
    /// When its last byte was written.
    written: Option<Instant>,
    bytes: usize,
}

/// Most frames on their way at once.
const MAX_DEPTH: usize = 3;
/// How long an answer may take before a terminal that never answered is
/// taken not to, and before one that did is taken to have lost one.
const FIRST_ANSWER: Duration = Duration::from_secs(1);
const LOST_ANSWER: Duration = Duration::from_secs(5);

/// Flow control and measurement of the way to the terminal: how many
/// frames may be on their way, and how fast the terminal drains them. Pure
/// bookkeeping over the times it is given, so it is tested without a
/// terminal.
#[derive(Clone, Debug)]
pub struct Link {
    period: Duration,
    acks: Acks,
    inflight: VecDeque<Sent>,
    /// The shortest round trip seen: the link's latency without a queue.
    min_rtt: Option<Duration>,
    /// Bytes per second the terminal drains, smoothed.
    rate: Option<f64>,
    last_ack: Option<Instant>,
    /// Whether the last frame came back within the latency and a frame
    /// period: if not, the terminal is behind and frames go one at a time.
    keeping_up: bool,
}

impl Link {
    /// Forgets the frames on their way (a frame cut short): the rate and
    /// latency measured so far are kept.
    pub fn forget_inflight(&mut self) {
        self.inflight = VecDeque::with_capacity(MAX_DEPTH + 1);
    }

    /// A link paced for `fps`; `caps` says whether the terminal answered
    /// the probe, and how fast.
    pub fn new(fps: u32, caps: &Capabilities, probed: bool) -> Link {
        Link {
            period: Duration::from_secs_f64(1.0 / fps.max(1) as f64),
            acks: match (probed, caps.answers_status) {
                (_, true) => Acks::Yes,
                (true, false) => Acks::No,
                (false, false) => Acks::Unknown,
            },
            inflight: VecDeque::with_capacity(MAX_DEPTH + 1),
            min_rtt: caps.round_trip,
            rate: None,
            last_ack: None,
            // Until the first frame comes back, the link is not known to
            // keep up: one frame at a time, so that none waits behind it.
            keeping_up: false,
        }
    }

    /// Whether to follow each frame with a status request.
    pub fn wants_acks(&self) -> bool {
        self.acks != Acks::No
    }

    /// How many frames may be on their way now.
    pub fn depth(&self) -> usize {
        match self.acks {
            Acks::No => 1,
            Acks::Unknown => MAX_DEPTH,
            Acks::Yes if !self.keeping_up => 1,
            Acks::Yes => {
                let latency = self.min_rtt.unwrap_or_default().as_secs_f64();
                let periods = (latency / self.period.as_secs_f64()).ceil() as usize;
                1 + periods.clamp(1, MAX_DEPTH - 1)
            }
        }
    }

    /// Whether a new frame may be sent at `now` (the previous one having
    /// been written in full).
    pub fn can_send(&mut self, now: Instant) -> bool {
        if self.acks == Acks::No {
            return true;
        }
        while let Some(front) = self.inflight.front() {
            let since = front.written.unwrap_or(front.start);
            let limit = if self.acks == Acks::Yes {
                LOST_ANSWER
            } else {
                FIRST_ANSWER
            };
            if now.saturating_duration_since(since) < limit {
                break;
            }
            if self.acks == Acks::Unknown {
                self.acks = Acks::No;
                self.inflight.clear();
            } else {
                self.inflight.pop_front();
            }
        }
        self.inflight.len() < self.depth()
    }

    /// A frame of `bytes` starts on its way at `now`.
    pub fn sent(&mut self, now: Instant, bytes: usize) {
        if self.inflight.len() > MAX_DEPTH {
            self.inflight.pop_front();
        }
        self.inflight.push_back(Sent {
            start: now,
            written: None,
            bytes,
        });
    }

    /// The last frame sent was written in full at `now`.
    pub fn written(&mut self, now: Instant) {
        let Some(last) = self.inflight.back_mut() else {
            return;
        };
        last.written = Some(now);
        if self.acks == Acks::No {
            // No answers: what the writes took is all there is to measure,
            // and only when they had to wait.
            let took = now.saturating_duration_since(last.start);
            let bytes = last.bytes as f64;
            if took > Duration::from_millis(5) {
                self.smooth(bytes / took.as_secs_f64());
            }
            self.inflight.clear();
        }
    }

    /// The terminal answered a status request at `now`: the oldest frame
    /// on its way has been drawn.
    pub fn acked(&mut self, now: Instant) {
        let Some(sent) = self.inflight.pop_front() else {
            return;
        };
        self.acks = Acks::Yes;
        if let Some(w) = sent.written {
            let rtt = now.saturating_duration_since(w);
            let min = self.min_rtt.map_or(rtt, |m| m.min(rtt));
            self.min_rtt = Some(min);
            self.keeping_up = rtt <= min + self.period;
        }
        // The terminal was busy with this frame from when it was sent, or
        // from when it finished the one before, whichever was later.
        let busy_from = self.last_ack.map_or(sent.start, |a| a.max(sent.start));
        let busy = now.saturating_duration_since(busy_from).as_secs_f64();
        if busy > 0.0 {
            self.smooth(sent.bytes as f64 / busy);
        }
        self.last_ack = Some(now);
    }

    fn smooth(&mut self, sample: f64) {
        self.rate = Some(self.rate.map_or(sample, |r| 0.7 * r + 0.3 * sample));
    }

    /// Bytes per second the terminal drains, when measured.
    pub fn rate(&self) -> Option<f64> {
        self.rate
    }

    /// Status requests sent and not yet answered.
    pub fn outstanding(&self) -> usize {
        if self.acks == Acks::No {
            0
        } else {
            self.inflight.len()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn answering(rtt_ms: u64) -> Capabilities {
        Capabilities {
            answers_status: true,
            round_trip: Some(Duration::from_millis(rtt_ms)),
            ..Capabilities::default()
        }
    }

    #[test]
    fn a_terminal_that_keeps_up_gets_two_frames_in_flight() {
        let t0 = Instant::now();
        let ms = |n| t0 + Duration::from_millis(n);
        let mut link = Link::new(30, &answering(1), true);
        assert!(link.wants_acks());
        assert_eq!(link.depth(), 1, "not known to keep up yet");
        link.sent(ms(0), 10_000);
        link.written(ms(0));
        assert!(!link.can_send(ms(1)));
        link.acked(ms(1));
        assert_eq!(link.depth(), 2);
        link.sent(ms(1), 10_000);
        link.written(ms(1));
        assert!(link.can_send(ms(1)));
        link.sent(ms(2), 10_000);
        link.written(ms(2));
        assert!(!link.can_send(ms(2)), "two on their way");
        link.acked(ms(3));
        assert!(link.can_send(ms(3)));
        assert_eq!(link.depth(), 2);
    }

    #[test]
    fn a_slow_link_gets_one_frame_at_a_time_and_its_rate_is_measured() {
        let t0 = Instant::now();
        let ms = |n| t0 + Duration::from_millis(n);
        let mut link = Link::new(30, &answering(2), true);
        // 32 kB at 16 kB/s: written at once (the kernel buffers it), drawn
        // two seconds later.
        link.sent(ms(0), 32_000);
        link.written(ms(1));
        link.acked(ms(2000));
        assert_eq!(link.depth(), 1, "behind: one frame at a time");
        let rate = link.rate().unwrap();
        assert!((rate - 16_000.0).abs() < 1.0, "{rate}");
        link.sent(ms(2000), 32_000);
        link.written(ms(2001));
        assert!(!link.can_send(ms(2500)), "waits for the answer");
        link.acked(ms(4000));
        assert!(link.can_send(ms(4000)));
    }

    #[test]
    fn a_terminal_that_never_answers_is_paced_by_writes() {
        let t0 = Instant::now();
        let ms = |n| t0 + Duration::from_millis(n);
        // Probed, no answer: no requests at all.
        let silent = Link::new(30, &Capabilities::default(), true);
        assert!(!silent.wants_acks());
        // Not probed: requests until a second passes without an answer.
        let mut link = Link::new(30, &Capabilities::default(), false);
        assert!(link.wants_acks());
        for i in 0..3 {
            assert!(link.can_send(ms(i)));
            link.sent(ms(i), 100);
            link.written(ms(i));
        }
        assert!(!link.can_send(ms(500)));
        assert!(link.can_send(ms(1100)));
        assert!(!link.wants_acks());
        // Writes that had to wait measure the rate.
        link.sent(ms(2000), 10_000);
        link.written(ms(3000));
        assert!((link.rate().unwrap() - 10_000.0).abs() < 1.0);
    }
}
