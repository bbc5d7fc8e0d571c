/*
 * drawing.h - what a task draws, as data: shapes with colours and labels,
 * and a fill colour per robot.  The PNG renderer reads it (render.h), and
 * so will every other view; no renderer knows a task.
 *
 * Lengths are metres in arena coordinates (origin at the centre, +y up).
 */
#ifndef SIM_DRAWING_H
#define SIM_DRAWING_H

#include <stdint.h>

typedef enum draw_kind {
    DRAW_DISC = 0,     /**< filled circle: x, y, radius */
    DRAW_RING = 1,     /**< circle outline: x, y, radius, line width */
    DRAW_RECT = 2,     /**< filled axis-aligned rectangle: x, y (centre), w, h */
    DRAW_LINE = 3,     /**< segment: x, y to x2, y2, line width */
    DRAW_LABEL = 4     /**< text at x, y (its lower left corner) */
} draw_kind_t;

typedef enum draw_layer {
    DRAW_FLOOR = 0,    /**< on the floor, under obstacles and robots */
    DRAW_OVER = 1      /**< over everything */
} draw_layer_t;

#define DRAW_TEXT_MAX 32

/* Robot fills that read well on the default body (drawing_t.robot_rgb,
 * render_robot_t.fill_rgb): one palette for every task that marks robots. */
#define DRAW_RGB_HL_RED       0xF08C8Cu
#define DRAW_RGB_HL_GREEN     0x8CDC8Cu
#define DRAW_RGB_HL_BLUE      0x8CA0F0u
#define DRAW_RGB_HL_YELLOW    0xF0DC5Au

/* What a legend entry stands for, and so how its swatch is drawn. */
typedef enum draw_key_kind {
    DRAW_KEY_ROBOT = 0,   /**< a robot fill (counted in the pictures' legend) */
    DRAW_KEY_AREA = 1,    /**< a floor area a task draws filled (a nest) */
    DRAW_KEY_RING = 2,    /**< a task's outline on the floor (a goal, a range) */
    DRAW_KEY_ITEM = 3,    /**< an item the cameras see (sim_item_t: food, a target) */
    DRAW_KEY_LINE = 4     /**< a task's lines (links between robots) */
} draw_key_kind_t;

/* One entry of a legend: a colour and what it means.  A task lists its
 * entries in task_def_t.legend, robot fills first, and its draw takes the
 * colours from that same table, so the legend cannot drift from what is
 * drawn.  Every view's legend is that table (sim_host/core/legend.h). */
typedef struct draw_key {
    uint32_t rgb;              /**< 0xRRGGBB; ROBOT: 0 the default body; ITEM: unused */
    const char *label;         /**< NULL ends a table */
    uint8_t kind;              /**< draw_key_kind_t (0: a robot fill) */
    uint8_t colour;            /**< ITEM: its hal_colour_t, drawn as the frames draw items */
} draw_key_t;

typedef struct draw_shape {
    uint8_t kind;              /**< draw_kind_t */
    uint8_t layer;             /**< draw_layer_t */
    uint32_t rgb;              /**< 0xRRGGBB */
    float x, y;                /**< m */
    float radius;              /**< DISC, RING, m */
    float w, h;                /**< RECT size, m */
    float x2, y2;              /**< LINE end, m */
    float line;                /**< RING, LINE width, m (0: one pixel) */
    char text[DRAW_TEXT_MAX];  /**< LABEL */
} draw_shape_t;

/** A task's picture of one step.  The caller owns the arrays. */
typedef struct drawing {
    draw_shape_t *shapes;
    uint32_t count, cap;       /**< shapes used, room for */
    uint32_t *robot_rgb;       /**< per robot body colour, 0 = the default */
    uint32_t robot_count;
} drawing_t;

/** Appends a shape; returns 0, or -1 when there is no room (it is dropped). */
int drawing_add(drawing_t *d, const draw_shape_t *shape);

#endif
