/*
 * test_base.c - what every part of the simulator shares (swarmsim/base.h):
 * SIM_ASSERT is on in the test builds and reports the condition with its
 * file and line, the library's own invariants fire (a robot id past the
 * run's robots), and out of memory inside a step ends the process with
 * status 1 and one message.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "sim_fixture.h"

#include "swarmsim/base.h"

static jmp_buf caught;
static char last_condition[128], last_file[256];
static int last_line;

/* An assert handler that returns to the test instead of aborting. */
static void catch_assert(const char *condition, const char *file, int line)
{
    snprintf(last_condition, sizeof last_condition, "%s", condition);
    snprintf(last_file, sizeof last_file, "%s", file);
    last_line = line;
    longjmp(caught, 1);
}

static void test_assert_reports_condition_and_place(void **state)
{
    (void)state;
    volatile int expected_line = 0;
    sim_assert_fn *previous = sim_set_assert_handler(catch_assert);
    if (setjmp(caught) == 0) {
        int two = 2;
        expected_line = __LINE__ + 1;
        SIM_ASSERT(two + two == 5);
        fail_msg("SIM_ASSERT did not fire");
    }
    sim_set_assert_handler(previous);
    assert_string_equal(last_condition, "two + two == 5");
    assert_non_null(strstr(last_file, "test_base.c"));
    assert_int_equal(last_line, expected_line);
}

/* The library's accessors check the robot id they are given. */
static void test_library_invariant_fires(void **state)
{
    (void)state;
    scenario_t *sc = fixture_idle_scenario(3, 2.0f);
    sim_t *sim = fixture_sim(sc, 1);
    double x, y, t;
    sim_assert_fn *previous = sim_set_assert_handler(catch_assert);
    last_condition[0] = '\0';
    if (setjmp(caught) == 0) {
        sim_robot_pose(sim, 3, &x, &y, &t);
        fail_msg("robot 3 of 3 was accepted");
    }
    sim_set_assert_handler(previous);
    assert_string_equal(last_condition, "i < sim->n");
    assert_non_null(strstr(last_file, "sim.c"));
    sim_robot_pose(sim, 2, &x, &y, &t);   /* the last robot is fine */
    sim_destroy(sim);
    scenario_free(sc);
    free(sc);
}

/* In a child: out of memory inside a step exits 1 with one line on stderr. */
static void test_out_of_memory_exits_1(void **state)
{
    (void)state;
    int fd[2];
    assert_int_equal(pipe(fd), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        dup2(fd[1], 2);
        close(fd[0]);
        sim_out_of_memory("a test's buffer");
    }
    close(fd[1]);
    char buf[256] = "";
    ssize_t n = 0, got;
    while ((got = read(fd[0], buf + n, sizeof buf - 1 - (size_t)n)) > 0) {
        n += got;
    }
    close(fd[0]);
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 1);
    assert_string_equal(buf, "swarmsim: out of memory for a test's buffer\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_assert_reports_condition_and_place),
        cmocka_unit_test(test_library_invariant_fires),
        cmocka_unit_test(test_out_of_memory_exits_1),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
