/*
 * base.h - what every part of the simulator shares: the one size of an
 * error message and how errors travel, the invariant check, and what
 * happens when memory runs out.
 *
 * Errors.  A function that can fail returns 0 (or a pointer) on success,
 * -1 (or NULL) on failure with a message in the caller's buffer of
 * SIM_ERR_MAX bytes: one line, no trailing newline, naming what is wrong
 * and where (a scenario's: "file:line: key.path: message").  A function
 * that passes an error up leaves the message as it is or prefixes it with
 * where it came from; whoever prints it adds the program's name
 * ("swarmsim: ").  Long messages are cut, never overrun.
 *
 * Invariants.  SIM_ASSERT(cond) checks what the code itself guarantees
 * (an index within its array, a count within its capacity, a phase in its
 * order), never input: bad input is an error message.  It is on unless
 * NDEBUG is defined (every build of the project, plain, ASan and TSan,
 * keeps it on); a failure calls the assert handler, which prints the
 * condition with its file and line, and then aborts.
 *
 * Out of memory.  While a run is being built (scenario_load, sim_create,
 * a model's or a task's create) an allocation that fails is an error like
 * any other, "out of memory for <what>", and what was built is freed.  A
 * step cannot fail: what it needs is allocated when the run is built, and
 * the few buffers that grow with what happens in a run (a step's events)
 * call sim_out_of_memory, which reports and ends the process with exit
 * status 1 (a run failed).
 */
#ifndef SWARMSIM_BASE_H
#define SWARMSIM_BASE_H

/** Bytes of every error buffer: `char err[SIM_ERR_MAX]`. */
#define SIM_ERR_MAX 512

/** Called on a failed SIM_ASSERT with the condition's text, file and line.
 *  If it returns, the process aborts. */
typedef void sim_assert_fn(const char *condition, const char *file, int line);

/** Replaces the assert handler (NULL: the default, which prints to stderr);
 *  returns the previous one.  For tests that check an assertion fires. */
sim_assert_fn *sim_set_assert_handler(sim_assert_fn *fn);

/** Reports a failed assertion and aborts. */
_Noreturn void sim_assert_failed(const char *condition, const char *file, int line);

#if !defined(NDEBUG) || defined(SIM_ENABLE_ASSERT)
#define SIM_ASSERT(condition) \
    ((condition) ? (void)0 : sim_assert_failed(#condition, __FILE__, __LINE__))
#else
#define SIM_ASSERT(condition) ((void)0)
#endif

/** Out of memory inside a step (see above): prints "swarmsim: out of
 *  memory for <what>" and exits with status 1. */
_Noreturn void sim_out_of_memory(const char *what);

#endif
