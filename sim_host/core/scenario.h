/*
 * scenario.h - a simulation scenario: arena, robots, objects, lights, the
 * controller and its parameters, noise, duration and seed.
 *
 * Scenario files are YAML with a strict schema (see scenario.c for every key,
 * its unit and range).  Lengths are metres, angles degrees, times seconds
 * unless a key's name says otherwise.
 */
#ifndef SIM_SCENARIO_H
#define SIM_SCENARIO_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "param.h"

#define SCENARIO_NAME_MAX 64
#define SCENARIO_PATH_MAX 512
#define SCENARIO_ERROR_MAX 512
#define SCENARIO_MAX_OBJECTS 4096
#define SCENARIO_MAX_LIGHTS 16
#define SCENARIO_CONTROLLER_PARAMS_MAX 512

typedef enum object_shape { SHAPE_CYLINDER = 0, SHAPE_BOX = 1 } object_shape_t;

/** A static obstacle. */
typedef struct object_def {
    int shape;          /**< object_shape_t: "cylinder" or "box" */
    float x, y;         /**< centre, m (arena centre is 0,0) */
    float radius;       /**< cylinder radius, m */
    float width, depth; /**< box size along its x and y, m */
    float angle;        /**< box rotation, degrees CCW */
    float height;       /**< m (for the camera and pictures) */
    int colour;         /**< hal_colour_t: "none", "red", "green", "blue" */
} object_def_t;

/** A point light (a lamp above the floor). */
typedef struct light_def {
    float x, y;         /**< m */
    float height;       /**< above the floor, m */
    float intensity;    /**< relative: 1 gives irradiance 1 at 1 m */
} light_def_t;

/** Where robots in the nest learn the nest's state (seed 000, 3.2). */
typedef enum foraging_info {
    INFO_BEACON = 0,  /**< a nest-beacon e-puck keeps the ledger, IR broadcast */
    INFO_GLOBAL = 1   /**< ideal: the simulator broadcasts the true values */
} foraging_info_t;

typedef enum placement { PLACE_RANDOM = 0, PLACE_NEST = 1, PLACE_GRID = 2 } placement_t;

typedef struct scenario {
    char name[SCENARIO_NAME_MAX];
    char path[SCENARIO_PATH_MAX];  /**< file it was read from */

    uint64_t seed;                 /**< base seed; repetition r uses seed + r */
    double duration;               /**< simulated time, s */
    uint16_t control_period_ms;    /**< one controller step, ms */
    uint16_t physics_substeps;     /**< Box2D sub-steps per control step */

    struct {
        float width, height;       /**< walled rectangle centred on 0,0, m */
        float wall_thickness;      /**< m */
    } arena;

    struct {
        uint8_t enabled;
        float x, y, diameter;      /**< grey floor circle, m */
    } nest;

    struct {
        uint32_t count;
        int placement;             /**< placement_t */
        float min_spacing;         /**< centre-to-centre when placing, m */
    } robots;

    uint32_t object_count;
    object_def_t objects[SCENARIO_MAX_OBJECTS];

    uint32_t light_count;
    light_def_t lights[SCENARIO_MAX_LIGHTS];

    struct {
        char name[32];             /**< a name registered in controllers.c */
        char policy[16];           /**< variant, for controllers that have some
                                        (forager: drtm, artm, frtm) */
        /** The controller's params struct, filled from its defaults and then
         *  from `controller.params`; interpreted by the controller. */
        union {
            uint8_t bytes[SCENARIO_CONTROLLER_PARAMS_MAX];
            double align_double;
            uint64_t align_u64;
        } params;
    } controller;

    struct {
        float aperture;            /**< half-angle of the sensing cone, deg */
        float range;               /**< beyond this the sensor reads ~0, m */
        float noise_rel;           /**< relative Gaussian sd of the value */
        float noise_abs;           /**< additive Gaussian sd, raw counts */
    } ir;

    struct {
        float dark;                /**< raw reading in the dark, counts */
        float half;                /**< irradiance at which the reading halves */
        float noise_rel;           /**< relative Gaussian sd */
    } ambient;

    struct {
        float fov;                 /**< horizontal field of view, deg */
        float range;               /**< objects farther away are not seen, m */
        uint16_t width_px, height_px; /**< frame the blob pixels refer to */
    } camera;

    struct {
        float range;               /**< centre-to-centre reach, m */
        float loss;                /**< probability a message is lost */
        float bearing_noise;       /**< Gaussian sd added to the bearing, deg */
        float range_noise_rel;     /**< relative Gaussian sd of the range */
        uint8_t quantise_bearing;  /**< report the receiving sensor's bearing */
        uint8_t blocked_by_robots; /**< robots also block line of sight */
        uint8_t payload_bits;      /**< 8 (libIrcom) or 16 (range-and-bearing turret) */
    } ircom;

    struct {
        float speed_noise_rel;     /**< per-wheel relative speed noise (sd) */
    } wheels;

    struct {
        uint32_t timeseries_every; /**< control steps between CSV rows */
    } output;

    /** The foraging task of seed 000 (section 2.3-2.4, 3.1).  Amounts of
     *  food are in tokens; energy in units (one token = token_energy). */
    struct {
        uint8_t enabled;
        uint32_t food_count;       /**< N_f tokens kept in the arena */
        float token_radius;        /**< m (seed: 3.5 cm diameter) */
        float token_height;        /**< m (seed: 4.2 cm) */
        float token_energy;        /**< units per token (1500) */
        float initial_food;        /**< F(0), tokens in the nest at start */
        float desired_food;        /**< F_d, tokens */
        float consumption;         /**< nest consumption C_rate, tokens/min */
        float move_cost;           /**< units per step per foraging robot */
        float oae_energy;          /**< E_a, units per obstacle-avoidance event */
        float robot_speed;         /**< v, m/s: foragers drive at it; T2 = L/(2v) */
        int information;           /**< foraging_info_t */
    } foraging;
} scenario_t;

/** One `--set key.path=value` override. */
typedef struct scenario_override {
    const char *text;              /**< "key.path=value" as given */
} scenario_override_t;

/** Fills `out` with every default (no file). */
void scenario_defaults(scenario_t *out);

/**
 * Reads `path`, applies `overrides` in order, validates, and fills `out`.
 * Returns 0, or -1 with a message in `err` that names the file, the line
 * and the key ("x.yaml:12: robots.count: expected an integer, got '2.5'").
 * On error `out` is unspecified.  The caller owns `out` (it is large:
 * allocate it on the heap).
 */
int scenario_load(const char *path, const scenario_override_t *overrides,
                  size_t override_count, scenario_t *out,
                  char err[SCENARIO_ERROR_MAX]);

/** Writes every key with its default, unit and range to `f` (for --help). */
void scenario_print_schema(FILE *file);

#endif
