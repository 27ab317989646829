#pragma once
// Running the tick's threads ahead of everything else on the machine: the real-time FIFO class
// (Linux SCHED_FIFO). On a 2-core VM shared with 1000 bots, threads of the normal class waited
// 3-8 ms for a CPU after waking, behind a bot of the idle class the kernel let finish its slice,
// or behind kernel threads (memory monitoring, compaction) of their own class: 1 overrun in
// about every other 1000-player run. In the FIFO class a woken thread takes a CPU at once
// (docs/PERFORMANCE.md, "1000 bots on the field"). The kernel keeps 5 % of every second for the
// other classes (sched_rt_runtime_us), so a runaway tick cannot lock the machine up.
#include <string>
#include <thread>

namespace foresight::server {

/// Puts `thread` (a pthread) in the FIFO class at `priority` (1-99). False, with `error` saying
/// why and what to grant, where the process may not (no CAP_SYS_NICE and RLIMIT_RTPRIO below
/// `priority`: containers by default); the thread then keeps its class.
bool make_realtime(std::thread::native_handle_type thread, int priority, std::string& error);

/// The thread's class is FIFO (tests, figures).
bool is_realtime(std::thread::native_handle_type thread);

}  // namespace foresight::server
