"""Seed 002's centralised planner (issue 16, "The planner"): which robot picks
up which target, in which order, planned offline with every target known.

The problem
-----------
Given

* ``m`` targets at positions ``p_1 .. p_m`` (world coordinates, m: the items
  of the scenario's ``targets:`` task, exactly as the simulator lays them out),
* the nest centre ``p_0``,
* ``n`` robots, each of capacity ``c`` (seed 002: 36 robots, ``c = 5``),
* the robots' speed ``v`` (0.100 m/s at e-puck scale) and the pick-up time
  ``tau`` (5 s per target),

choose ``n`` open routes ``r_i = (t_i1, .., t_ic)``, each of **exactly** ``c``
distinct targets, no target in two routes, so that ``n c`` targets are visited
(seed 002: 36 x 5 = 180 = the stop count, 90 % of 200; the other ``m - n c``
are left out, and the plan chooses which).  Robot ``i`` leaves the nest
centre, drives straight to its targets in order and picks each up; it
finishes at

    T_i = L_i / v + tau c,   L_i = |p_0 p_i1| + |p_i1 p_i2| + .. + |p_i(c-1) p_ic|

(the return to the nest does not count: the run's time is the moment the
180th target is picked up).  The planner minimises the latest finishing time

    T = max_i T_i

(the plan's estimate of the foraging time, a lower bound for the simulated
robots, which also turn, avoid each other and leave the nest from their own
start positions).  Because T depends on the longest route only, the search
minimises ``T + lambda mean_i T_i`` (lambda = ``tiebreak``, 0.01 by default: a
second of T outweighs 100 s of the mean), so that among plans of equal T the
shorter ones win; every figure reported is T itself.

The modules
-----------
``problem``     the problem above, the distances, a plan's times and lengths,
                and the targets of a scenario read from the simulator
``alns``        the search (the ``alns`` package: roulette-wheel operator
                selection, simulated-annealing acceptance) with this package's
                destroy and repair operators, and the command line
                ``python -m swarmtools.plan.alns``
``crosscheck``  the same instance solved by PyVRP as a distance-minimising
                VRP, to compare total route lengths
"""
