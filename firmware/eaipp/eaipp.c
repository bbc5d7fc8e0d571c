/*
 * eaipp.c - EAIPP's states and mechanisms (see eaipp.h).  Section numbers
 * and algorithms are those of the paper (seed 003).
 */
#include "eaipp.h"

#include "repatt/odometry.h"

#define Q14 16384.0f
#define HALF_PI_MRAD 1571

static const char *const state_names[] = { "lost", "explorer", "node", "nest", "food", "exiting" };

void eaipp_default_params(eaipp_params_t *p)
{
    p->role = EAIPP_ROLE_ROBOT;
    p->speed_steps_s = 388u;       /* 5 cm/s, Table 2 */
    /* Algorithm 4: "if measured_distance(Object_N) > B_UL", with Table 2's
     * 0.7 R < B_UL < 0.8 R: a threshold, the middle of the interval
     * (R = 0.6 m).  No upper bound: an explorer that enters the range of a
     * lone node from outside becomes a node at once (a window (0.7 R, 0.8 R]
     * let such explorers cross the range without joining, and get lost). */
    p->b_ul_mm = 450u;
    p->b_ul_max_mm = 0u;
    /* PERIOD_TIME_1 and _2 are not given.  An explorer at 5 cm/s crosses one
     * link (0.75 R = 0.45 m) in 9 s: a branch end waits 3 links' travel
     * (30 s) for an explorer before leaving, and contracts when explorers
     * have been around it for 30 s without extending it. */
    p->period1_steps = 300u;
    p->period2_steps = 300u;
    /* A neighbour not heard for this long is forgotten.  A node's fields come
     * in three frames (three periods on a one-message turret, one period on
     * the e-RandB images' three): without loss 10 periods would do, but a
     * neighbour still in range is forgotten with probability loss^timeout,
     * and the robustness tests (Figure 16) go to a loss of 0.8:
     * 0.8^10 = 11 % (nodes lost their parents and left, explorers got lost:
     * 0/20 merged at D = 3 m), 0.8^30 = 0.1 % (5/20).  30 periods (3 s)
     * change nothing without loss (D = 1.4, 3.0 m: 15 and 10 of 20, against
     * 15 and 9 with 10). */
    p->timeout_steps = 30u;
    p->w_nodes = 1.0f;
    p->w_obstacles = 1.0f;
    p->prox_full = 1000u;          /* ~1 cm from a surface reads 1 */
    p->lost_turn_prox = 300u;      /* ~2.5 cm */
    /* Eq 1 lost its symbols: D_i may divide or multiply the node term.
     * With 1/D_i the highest node heard is a point attractor: an explorer
     * reaching the end node of a branch is held against its body, in range
     * of the node before it (0.45 m back: an e-puck touching the end node is
     * 0.08 m from it; a marXbot, 17 cm wide, would be 0.17 m off and nearly
     * out of that range), so Algorithm 4 (exactly one node heard) never
     * fires and the end contracts with explorers around it.  With D_i u_i
     * (the vector to the neighbour) the term is sum (g_i - g_mean) x_i, one
     * direction down the branch wherever the explorer is: it passes the end
     * node and extends the branch.  We take the linear reading. */
    p->a_distance = EAIPP_A_LINEAR;
    p->ext_strict = 0u;
    p->turn_hold_mrad = 400u;      /* two periods of an e-puck's spin at 5 cm/s (0.19 rad each) */
    /* The food is the target, not a source (Algorithm 4 and eq 1 count
     * Robot_Node and Robot_Nest only; section 5.2 ends a run when the food
     * is perceived).  With the food a source as well, two networks grown by
     * Algorithm 4 never merge: an explorer becomes a node only where it
     * hears exactly one node, so the new node is out of range of the other
     * network's nodes. */
    p->food_source = 0u;
    /* A merge rule the text does not print (it is needed for two sources):
     * an explorer belongs to the network whose nodes it hears, the nest's
     * when it hears both. Off: the printed rules. */
    p->same_source = 0u;
    /* Section 5.1's exit from the waiting area: off (the square arena's
     * robots start anywhere).  sigma 150 mm: exiting e-pucks (74 mm) settle
     * 168 mm apart, two bodies; the exit is done 250 mm from the nest (the
     * half-scale maze's door is 0.25 m from it). */
    p->lj_exit = 0u;
    p->lj_sigma_mm = 150u;
    p->lj_weight = 1.0f;
    p->exit_near_mm = 250u;
}

void eaipp_init(eaipp_t *self, const eaipp_params_t *params, uint32_t seed)
{
    self->p = *params;
    self->seed = seed;
    eaipp_reset(self);
}

void eaipp_reset(eaipp_t *self)
{
    rng_seed(&self->rng, self->seed);
    neighbours_clear(&self->nb);
    self->state = self->p.role == EAIPP_ROLE_NEST ? (uint8_t)EAIPP_NEST
        : self->p.role == EAIPP_ROLE_FOOD ? (uint8_t)EAIPP_FOOD : (uint8_t)EAIPP_LOST;
    self->id = 0u;
    self->gradient = self->state == EAIPP_LOST ? (uint8_t)EAIPP_GRADIENT_MAX : 0u;
    self->source = self->state == EAIPP_FOOD ? (uint8_t)EAIPP_SOURCE_FOOD : (uint8_t)EAIPP_SOURCE_NEST;
    self->root = 0u;
    self->parent = 0u;
    self->children = 0u;
    self->contraction = 0u;
    self->tx_cursor = 0u;
    self->turning = 0u;
    self->turn_dir = 1;
    self->turn_side = 0;
    self->shun_root = 0u;
    self->shun_parent = 0u;
    self->shun_steps = 0u;
    self->counter1 = 0u;
    self->counter2 = 0u;
    self->orphan_steps = 0u;
    self->exited = 0u;
    self->retreating = 0u;
    self->exit_mm = 0xFFFFu;
    self->heading_x = 1.0f;
    self->heading_y = 0.0f;
    self->joins = 0u;
    self->leaves = 0u;
}

const char *eaipp_state_name(const eaipp_t *self)
{
    return self->state < 6u ? state_names[self->state] : "?";
}

/* ------------------------------------------------------------ the table */

/* Whether a neighbour is a gradient holder (a node with a gradient heard,
 * the nest, or the food when food_source is set) and its gradient and
 * Source_Type.  By default (food_source 0, the printed Algorithm 4 and eq 1,
 * and section 5.1's maze rule) the food is no source: the network grows from
 * the nest only. */
static uint8_t holder(const eaipp_t *self, const neighbour_t *n, uint8_t *g, uint8_t *src)
{
    if (neighbour_is(n, EAIPP_ST_NEST)) {
        *g = 0u;
        *src = EAIPP_SOURCE_NEST;
        return 1u;
    }
    if (neighbour_is(n, EAIPP_ST_FOOD)) {
        *g = 0u;
        *src = EAIPP_SOURCE_FOOD;
        return (uint8_t)(self->p.food_source != 0u);
    }
    if (neighbour_is(n, EAIPP_ST_NODE) && (n->heard & NB_HEARD_GRADIENT) != 0u
        && n->gradient < EAIPP_GRADIENT_MAX) {
        *g = n->gradient;
        *src = neighbour_gradient_source(n);
        return 1u;
    }
    return 0u;
}

/* The Source_Type an explorer belongs to under same_source: the nest's when
 * it hears a nest-sourced holder, else the food's. */
static uint8_t own_source(const eaipp_t *self)
{
    uint8_t i, g, src;
    for (i = 0; i < self->nb.count; i++) {
        if (holder(self, &self->nb.n[i], &g, &src) && src == EAIPP_SOURCE_NEST) {
            return EAIPP_SOURCE_NEST;
        }
    }
    return EAIPP_SOURCE_FOOD;
}

/* Whether neighbour n counts for this explorer's Algorithm 4 and eq 1: a
 * holder (holder()), and under same_source (with food_source) one of
 * `mine`, the explorer's own Source_Type. */
static uint8_t counts(const eaipp_t *self, const neighbour_t *n, uint8_t mine, uint8_t *g, uint8_t *src)
{
    if (!holder(self, n, g, src)) {
        return 0u;
    }
    return (uint8_t)(self->p.same_source == 0u || self->p.food_source == 0u || *src == mine);
}

/* A node (or the nest) the robot is shunning: the branch it left (section
 * 4.2.1: "a Robot_Node that leaves the network due to the extinction
 * mechanism will not rejoin the same branch chain").  The branch is the
 * Root_ID the robot had, and also its old P_Node by id: the Root_ID of a
 * fork changes when the leaving child was one of its two, so that by Root_ID
 * alone the robot rejoined its parent at once, in the same place.  The nest
 * (Root_ID = own id) is shunned like a node: a node next to the nest that
 * left would otherwise rejoin it the next step. */
static uint8_t shunned(const eaipp_t *self, const neighbour_t *n)
{
    if (self->shun_steps == 0u || !(neighbour_is(n, EAIPP_ST_NODE) || neighbour_is(n, EAIPP_ST_NEST))) {
        return 0u;
    }
    return (uint8_t)(n->id == self->shun_parent || ((n->heard & NB_HEARD_ROOT) != 0u && n->root == self->shun_root));
}

/* What a lost or exploring robot senses: the nest, a node, or the food when
 * it is a source (food_source).  Otherwise the food alone does not count,
 * only with a node near (section 5.1's rule; section 4.3: a lost robot walks
 * "until it perceives a Robot_Node or the Robot_Nest again").  Shunned
 * nodes do not count, except for a node that left a contracting branch as
 * an explorer (Algorithm 2): it must "move back along this branch towards
 * other branches", guided by the branch it shuns (it still may not join
 * it); by the shunning alone it was lost the step after it left. */
static uint8_t senses_network(const eaipp_t *self)
{
    uint8_t i, node = 0u, food = 0u;
    for (i = 0; i < self->nb.count; i++) {
        const neighbour_t *n = &self->nb.n[i];
        uint8_t ok = (uint8_t)(self->retreating != 0u || !shunned(self, n));
        if (neighbour_is(n, EAIPP_ST_NEST) && ok) {
            return 1u;
        }
        if (neighbour_is(n, EAIPP_ST_NODE) && ok) {
            node = 1u;
        }
        if (neighbour_is(n, EAIPP_ST_FOOD)) {
            food = 1u;
        }
    }
    return (uint8_t)(node != 0u || (food != 0u && self->p.food_source != 0u));
}

/* ---------------------------------------------------- Algorithm 1: gradient */

uint8_t eaipp_gradient_update(eaipp_t *self)
{
    /* The pseudocode assigns neighbor_min_gradient_1 to itself (and the
     * food branch to _1); the evident intent, done here: the minimum over
     * nest-sourced neighbours in min1, over food-sourced ones in min2, and
     * a nest gradient wins over a food one whatever their values. */
    uint8_t min1 = EAIPP_GRADIENT_MAX, min2 = EAIPP_GRADIENT_MAX;
    uint8_t par1 = 0u, par2 = 0u, i;
    const neighbour_t *parent = 0;
    for (i = 0; i < self->nb.count; i++) {
        uint8_t g, src;
        if (!holder(self, &self->nb.n[i], &g, &src)) {
            continue;
        }
        if (src == EAIPP_SOURCE_NEST) {
            if (g < min1) {
                min1 = g;
                par1 = i;
            }
        } else if (g < min2) {
            min2 = g;
            par2 = i;
        }
    }
    if (min1 < EAIPP_GRADIENT_MAX) {
        self->source = EAIPP_SOURCE_NEST;
        self->gradient = (uint8_t)(min1 + 1u);
        parent = &self->nb.n[par1];
    } else if (min2 < EAIPP_GRADIENT_MAX) {
        self->source = EAIPP_SOURCE_FOOD;
        self->gradient = (uint8_t)(min2 + 1u);
        parent = &self->nb.n[par2];
    } else {
        self->gradient = EAIPP_GRADIENT_MAX;
        self->children = 0u;
        return 0u;
    }
    if (self->gradient > EAIPP_GRADIENT_LAST) {
        self->gradient = EAIPP_GRADIENT_MAX;   /* counted to "infinity": no gradient */
        self->children = 0u;
        return 0u;
    }
    self->parent = parent->id;
    /* C_Nodes: nodes of my source one hop farther. */
    self->children = 0u;
    for (i = 0; i < self->nb.count; i++) {
        uint8_t g, src;
        const neighbour_t *n = &self->nb.n[i];
        if (neighbour_is(n, EAIPP_ST_NODE) && holder(self, n, &g, &src) && src == self->source
            && g == (uint8_t)(self->gradient + 1u)) {
            self->children++;
        }
    }
    /* Root_ID: mine where the branch forks, else the parent's (a source's
     * Root_ID is its own id, which it also sends). */
    if (self->children >= 2u) {
        self->root = self->id;
    } else if ((parent->heard & NB_HEARD_ROOT) != 0u) {
        self->root = parent->root;
    } else {
        self->root = parent->id;
    }
    return 1u;
}

/* -------------------------------------------------- Algorithm 2: extinction */

static void leave(eaipp_t *self, uint8_t state)
{
    self->shun_root = self->root;
    self->shun_parent = self->parent;
    self->shun_steps = self->p.period1_steps;
    self->retreating = (uint8_t)(state == EAIPP_EXPLORER);
    self->state = state;
    self->counter1 = 0u;
    self->counter2 = 0u;
    self->leaves++;
}

void eaipp_extinction_step(eaipp_t *self)
{
    uint8_t i;
    if (self->children == 0u) {
        /* The end of a branch: is any explorer around? */
        uint8_t explorer = 0u;
        for (i = 0; i < self->nb.count; i++) {
            if (neighbour_is(&self->nb.n[i], EAIPP_ST_EXPLORER)) {
                explorer = 1u;
                break;
            }
        }
        if (explorer) {
            if (self->counter2 < 0xFFFFu) self->counter2++;
            self->counter1 = 0u;
        } else {
            if (self->counter1 < 0xFFFFu) self->counter1++;
            self->counter2 = 0u;
        }
        if (self->contraction == 0u) {
            if (self->counter1 > self->p.period1_steps) {
                /* Explorers could reach this end but none came for long. */
                leave(self, EAIPP_LOST);
            } else if (self->counter2 > self->p.period2_steps) {
                /* Explorers came but no child was made: contract.  The
                 * pseudocode also sets Robot_Explorer here; the text has the
                 * end node broadcast the flag, wait for the explorers to
                 * leave and only then (PERIOD_TIME_1 without explorers, the
                 * rule below) leave: we follow the text. */
                self->contraction = 1u;
                self->counter1 = 0u;
                self->counter2 = 0u;
            }
        } else if (self->counter1 > self->p.period1_steps) {
            /* Contracting and deserted: leave, back along the branch, unless
             * this is the last node before the fork (kept as a marker). */
            if (self->root != self->parent) {
                leave(self, EAIPP_EXPLORER);
            } else {
                self->counter1 = 0u;
            }
        }
    } else if (self->children >= 2u) {
        /* A fork (Root_ID = own id) is the root of the branches below it,
         * not one of their members: their Root_ID is its id, so the printed
         * "Root_ID(n) = Root_ID(self)" would have it take the flag of
         * whichever child it heard first and repel explorers from its other,
         * healthy branches.  The flag stops at the last node before the fork
         * (Algorithm 2's marker). */
        self->counter1 = 0u;
        self->counter2 = 0u;
        self->contraction = 0u;
    } else {
        self->counter1 = 0u;
        self->counter2 = 0u;
        /* Forward the child's flag along my branch. */
        for (i = 0; i < self->nb.count; i++) {
            uint8_t g, src;
            const neighbour_t *n = &self->nb.n[i];
            if (neighbour_is(n, EAIPP_ST_NODE) && holder(self, n, &g, &src) && src == self->source
                && g == (uint8_t)(self->gradient + 1u) && (n->heard & NB_HEARD_ROOT) != 0u
                && n->root == self->root) {
                self->contraction = neighbour_contraction(n);
                break;
            }
        }
    }
}

/* --------------------------------------------------- Algorithm 4: extension */

/* Exactly one Robot_Node or Robot_Nest heard (the food too when it is a
 * source), not contracting, farther than B_UL: become a node (the printed
 * last line's "state <- Robot_Explorer" read as Robot_Node). */

uint8_t eaipp_extension_due(const eaipp_t *self)
{
    uint8_t i, count = 0u, g, src;
    uint8_t same = (uint8_t)(self->p.same_source != 0u && self->p.food_source != 0u);
    uint8_t mine = same != 0u ? own_source(self) : (uint8_t)EAIPP_SOURCE_NEST;
    const neighbour_t *only = 0;
    for (i = 0; i < self->nb.count; i++) {
        const neighbour_t *n = &self->nb.n[i];
        if (same != 0u) {
            /* Only the holders of its own network count; a node whose
             * gradient is not heard yet cannot be placed: wait. */
            if (neighbour_is(n, EAIPP_ST_NODE) && ((n->heard & NB_HEARD_GRADIENT) == 0u)) {
                return 0u;
            }
            if (counts(self, n, mine, &g, &src)) {
                count++;
                only = n;
            }
        } else if (neighbour_is(n, EAIPP_ST_NODE) || neighbour_is(n, EAIPP_ST_NEST)
            || (neighbour_is(n, EAIPP_ST_FOOD) && self->p.food_source != 0u)) {
            count++;
            only = n;
        } else if (self->p.ext_strict != 0u && (n->heard & NB_HEARD_STATE) == 0u) {
            /* ext_strict: heard, but its STATE frame not yet (a node's comes
             * every third period): it may be a node, and "exactly one"
             * cannot be decided.  Wait. */
            return 0u;
        }
    }
    if (count != 1u || neighbour_contraction(only) || shunned(self, only)) {
        return 0u;
    }
    /* ext_strict: measured_distance from this period's message only, not a
     * range the table kept from an earlier one (lost messages leave it up to
     * `timeout` - 1 periods old: at most 45 mm of an explorer's travel).
     * Off by default: no change without loss, and under heavy loss (0.8)
     * explorers waiting for a current range drifted out of reach (D = 1.4 m,
     * 60 seeds: 22 merged strict, 33 not). */
    if (self->p.ext_strict != 0u && only->age != 0u) {
        return 0u;
    }
    /* A node must have a gradient to extend from. */
    if (neighbour_is(only, EAIPP_ST_NODE)
        && ((only->heard & NB_HEARD_GRADIENT) == 0u || only->gradient >= EAIPP_GRADIENT_MAX)) {
        return 0u;
    }
    return (uint8_t)(only->range_mm > self->p.b_ul_mm
                     && (self->p.b_ul_max_mm == 0u || only->range_mm <= self->p.b_ul_max_mm));
}

/* ------------------------------------------------------ eq 1 and Algorithm 3 */

void eaipp_direction(const eaipp_t *self, const uint16_t prox[HAL_IR_COUNT], const int16_t bearing_mrad[HAL_IR_COUNT],
                     float *vx, float *vy)
{
    /* Eq 1 lost its symbols; from its description we take
     *   V = w_n (1 - p_max) A/|A| + w_o p_max B/|B|
     *   A = (1/N) sum_i F_i (g_i - g_mean) D_i u_i   over the N nodes and
     *       sources heard: g_i their gradients, g_mean their mean, u_i the
     *       unit vector toward i, D_i its range (m), F_i = +1, or -1 when i
     *       carries Flag_Contraction (explorers then retreat down the branch);
     *       with a_distance = inverse, u_i / D_i instead (see the default)
     *   B = sum_j p_j (-v_j)   over the proximity sensors: p_j the reading
     *       scaled to [0, 1] (prox_full reads 1), v_j the sensor's direction
     *   p_max = max_j p_j: the nearer an obstacle, the more it dominates.
     * When A vanishes (one node, or all at one gradient) the robot keeps
     * its heading (A = ahead), so that it leaves the lone node outward. */
    float ax = 0.0f, ay = 0.0f, bx = 0.0f, by = 0.0f, mean = 0.0f, pmax = 0.0f, len;
    uint8_t i, n = 0u;
    uint8_t mine = (self->p.same_source != 0u && self->p.food_source != 0u) ? own_source(self)
                                                                             : (uint8_t)EAIPP_SOURCE_NEST;
    for (i = 0; i < self->nb.count; i++) {
        uint8_t g, src;
        if (counts(self, &self->nb.n[i], mine, &g, &src)) {
            mean += (float)g;
            n++;
        }
    }
    if (n > 0u) {
        mean /= (float)n;
        for (i = 0; i < self->nb.count; i++) {
            const neighbour_t *nb = &self->nb.n[i];
            uint8_t g, src;
            float d, w;
            if (!counts(self, nb, mine, &g, &src)) {
                continue;
            }
            d = (float)(nb->range_mm < 10u ? 10u : nb->range_mm) / 1000.0f;
            w = self->p.a_distance == EAIPP_A_LINEAR ? ((float)g - mean) * d : ((float)g - mean) / d;
            if (neighbour_contraction(nb)) {
                w = -w;
            }
            ax += w * (float)odo_cos_q14(nb->bearing_mrad) / Q14;
            ay += w * (float)odo_sin_q14(nb->bearing_mrad) / Q14;
        }
    }
    len = ax * ax + ay * ay;
    if (len < 1e-6f) {
        ax = 1.0f;
        ay = 0.0f;
    }
    for (i = 0; i < HAL_IR_COUNT; i++) {
        float pj = (float)prox[i] / (float)self->p.prox_full;
        if (pj > 1.0f) pj = 1.0f;
        if (pj > pmax) pmax = pj;
        bx -= pj * (float)odo_cos_q14(bearing_mrad[i]) / Q14;
        by -= pj * (float)odo_sin_q14(bearing_mrad[i]) / Q14;
    }
    /* Normalise both terms (|.| by the larger component: no sqrt needed for
     * a direction, and the weights keep their meaning within a factor 1.41). */
    {
        float ma = ax < 0 ? -ax : ax, mb = bx < 0 ? -bx : bx, t;
        t = ay < 0 ? -ay : ay;
        if (t > ma) ma = t;
        t = by < 0 ? -by : by;
        if (t > mb) mb = t;
        *vx = self->p.w_nodes * (1.0f - pmax) * ax / ma;
        *vy = self->p.w_nodes * (1.0f - pmax) * ay / ma;
        if (mb > 1e-6f) {
            *vx += self->p.w_obstacles * pmax * bx / mb;
            *vy += self->p.w_obstacles * pmax * by / mb;
        }
    }
}

void eaipp_wheel_law(float vx, float vy, uint16_t speed, uint16_t hold_mrad, int8_t *side, int16_t *left,
                     int16_t *right)
{
    /* Algorithm 3: angle between the heading and V; the inner wheel slows
     * by (1 - 2|angle|/pi), reversing beyond a right angle.  The pseudocode
     * writes (1 - 2 angle/pi) for negative angles too, which would speed the
     * inner wheel up: the evident intent is |angle|.
     *
     * Modelling correction (the paper is silent): a direction behind the
     * robot, within hold_mrad of +-pi, keeps the side of the last turn
     * (*side).  The turret's bearings are one control period old and a
     * robot turning toward a target behind it spins at the full 2 v / L
     * (0.19 rad a period for an e-puck at 5 cm/s): the sign of the angle
     * flips every period and the robot dithered in place for hundreds of
     * steps. */
    int32_t a = odo_atan2_mrad((int32_t)(vy * 1000.0f), (int32_t)(vx * 1000.0f));
    int32_t mag = a < 0 ? -a : a;
    int32_t slow;
    if (mag > 2 * HALF_PI_MRAD - (int32_t)hold_mrad && *side != 0) {
        a = *side > 0 ? mag : -mag;
    }
    slow = (int32_t)speed - (int32_t)speed * 2 * mag / (2 * HALF_PI_MRAD);
    if (a > 0) {
        *left = (int16_t)slow;
        *right = (int16_t)speed;
        *side = 1;
    } else {
        *left = (int16_t)speed;
        *right = (int16_t)slow;
        *side = (int8_t)(a < 0 ? -1 : 0);
    }
}

/* ------------------------------------------------- section 5.1: exiting */

uint8_t eaipp_exit_direction(eaipp_t *self, float *vx, float *vy)
{
    /* "the robots are attracted to the Robot_Nest, maintain a safe distance
     * from other exiting robots based on the LJ model, and broadcast their
     * distances from the Robot_Nest ... The robots that cannot perceive the
     * Robot_Nest directly are attracted to their neighbours that are
     * broadcasting the shortest distances to the landmark."  The pull is a
     * unit vector toward the nest or that neighbour (own distance: its
     * distance plus the range to it); each exiting neighbour j adds
     * -lj_weight f(r_j) u_j with the Lennard-Jones shape
     * f(r) = (s/r)^12 - (s/r)^6 (s = sigma; repulsive below 2^(1/6) s,
     * weakly attractive above), clamped to [-1, 1]. */
    const neighbour_t *target = 0;
    uint32_t best = 0xFFFFFFFFu;
    float ax = 0.0f, ay = 0.0f;
    uint8_t i;
    for (i = 0; i < self->nb.count; i++) {
        const neighbour_t *n = &self->nb.n[i];
        uint32_t d;
        if (neighbour_is(n, EAIPP_ST_NEST)) {
            d = n->range_mm;
        } else if (neighbour_is(n, EAIPP_ST_EXITING) && (n->heard & NB_HEARD_EXIT) != 0u
                   && n->exit_units < EAIPP_MSG_EXIT_UNKNOWN) {
            d = (uint32_t)n->exit_units * EAIPP_MSG_EXIT_MM + n->range_mm;
        } else {
            continue;
        }
        if (d < best) {
            best = d;
            target = n;
        }
    }
    if (target == 0) {
        self->exit_mm = 0xFFFFu;
        return 0u;
    }
    self->exit_mm = (uint16_t)(best > 0xFFFEu ? 0xFFFEu : best);
    ax = (float)odo_cos_q14(target->bearing_mrad) / Q14;
    ay = (float)odo_sin_q14(target->bearing_mrad) / Q14;
    for (i = 0; i < self->nb.count; i++) {
        const neighbour_t *n = &self->nb.n[i];
        float q, q6, f;
        if (!neighbour_is(n, EAIPP_ST_EXITING)) {
            continue;
        }
        q = (float)self->p.lj_sigma_mm / (float)(n->range_mm < 10u ? 10u : n->range_mm);
        q6 = q * q * q;
        q6 = q6 * q6;
        f = q6 * q6 - q6;
        if (f > 1.0f) f = 1.0f;
        if (f < -1.0f) f = -1.0f;
        f *= self->p.lj_weight;
        ax -= f * (float)odo_cos_q14(n->bearing_mrad) / Q14;
        ay -= f * (float)odo_sin_q14(n->bearing_mrad) / Q14;
    }
    *vx = ax;
    *vy = ay;
    return 1u;
}

/* Whether a lost robot of the waiting area starts exiting: it hears the nest
 * or an exiting robot (section 5.1: "other robots detect the presence of
 * robots in the exiting state and switch to the same state"). */
static uint8_t exit_due(const eaipp_t *self)
{
    uint8_t i;
    if (self->p.lj_exit == 0u || self->exited != 0u) {
        return 0u;
    }
    for (i = 0; i < self->nb.count; i++) {
        if (neighbour_is(&self->nb.n[i], EAIPP_ST_NEST) || neighbour_is(&self->nb.n[i], EAIPP_ST_EXITING)) {
            return 1u;
        }
    }
    return 0u;
}

/* Eq 1's blend of a direction with the obstacle term, for exiting robots. */
static void blend_obstacles(const eaipp_t *self, const uint16_t prox[HAL_IR_COUNT],
                            const int16_t bearing_mrad[HAL_IR_COUNT], float *vx, float *vy)
{
    float bx = 0.0f, by = 0.0f, pmax = 0.0f, ma, mb, t;
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        float pj = (float)prox[i] / (float)self->p.prox_full;
        if (pj > 1.0f) pj = 1.0f;
        if (pj > pmax) pmax = pj;
        bx -= pj * (float)odo_cos_q14(bearing_mrad[i]) / Q14;
        by -= pj * (float)odo_sin_q14(bearing_mrad[i]) / Q14;
    }
    ma = *vx < 0 ? -*vx : *vx;
    t = *vy < 0 ? -*vy : *vy;
    if (t > ma) ma = t;
    if (ma < 1e-6f) {
        *vx = 1.0f;
        *vy = 0.0f;
        ma = 1.0f;
    }
    mb = bx < 0 ? -bx : bx;
    t = by < 0 ? -by : by;
    if (t > mb) mb = t;
    *vx = (1.0f - pmax) * *vx / ma;
    *vy = (1.0f - pmax) * *vy / ma;
    if (mb > 1e-6f) {
        *vx += pmax * bx / mb;
        *vy += pmax * by / mb;
    }
}

/* ------------------------------------------------------------------ steps */

static void hear_all(eaipp_t *self, hal_t *hal)
{
    hal_ircom_msg_t m;
    eaipp_msg_t d;
    neighbours_age(&self->nb, self->p.timeout_steps);
    while (hal_ircom_receive(hal, &m) == HAL_OK) {
        if (eaipp_msg_decode(m.value, &d) && d.id != self->id) {
            (void)neighbours_hear(&self->nb, &d, m.range_mm, m.bearing_mrad);
        }
    }
}

static void send_turn(eaipp_t *self, hal_t *hal)
{
    /* Nodes and sources cycle STATE, GRADIENT, ROOT; lost robots and
     * explorers have only their STATE to say.  As many as the platform
     * takes this period, at most one cycle. */
    uint8_t cycle = (self->state == EAIPP_LOST || self->state == EAIPP_EXPLORER) ? 1u
        : self->state == EAIPP_EXITING ? 2u : 3u;
    uint8_t k;
    for (k = 0; k < cycle; k++) {
        uint16_t f;
        uint8_t kind = (uint8_t)(self->tx_cursor % cycle);
        if (kind == 0u) {
            f = eaipp_msg_state(self->id, self->state, self->source, self->contraction);
        } else if (self->state == EAIPP_EXITING) {
            /* Exiting robots alternate STATE and EXIT (their distance to the nest). */
            f = eaipp_msg_exit(self->id, self->exit_mm, (uint8_t)(self->exit_mm != 0xFFFFu));
        } else if (kind == 1u) {
            f = eaipp_msg_gradient(self->id, self->source, self->gradient);
        } else {
            f = eaipp_msg_root(self->id, self->root);
        }
        if (hal_ircom_send(hal, f) != HAL_OK) {
            break;
        }
        self->tx_cursor = (uint8_t)((self->tx_cursor + 1u) % cycle);
    }
}

static void read_prox(hal_t *hal, uint16_t prox[HAL_IR_COUNT], int16_t bearing[HAL_IR_COUNT])
{
    uint8_t i;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        prox[i] = hal_ir_proximity(hal, i);
        bearing[i] = hal_ir_bearing_mrad(hal, i);
    }
}

static void become_node(eaipp_t *self, hal_t *hal)
{
    self->state = EAIPP_NODE;
    self->retreating = 0u;
    self->contraction = 0u;
    self->counter1 = 0u;
    self->counter2 = 0u;
    self->joins++;
    (void)eaipp_gradient_update(self);
    hal_set_wheel_speeds(hal, 0, 0);
}

static void lost_step(eaipp_t *self, hal_t *hal, const uint16_t prox[HAL_IR_COUNT],
                      const int16_t bearing[HAL_IR_COUNT])
{
    /* Sections 4.1, 4.3: "the robot keeps moving in a straight line ... when
     * encountering the boundary of the environment or with other robots ...
     * changes the direction of movement to avoid collisions".  Only what is
     * ahead (a sensor within +-90 deg of the heading, exclusive) starts a
     * turn: a robot that has turned its back to a wall drives away from it.
     * (Turning on the rear sensors too kept robots spinning in the corners
     * for hundreds of steps: after a turn away from a wall the rear sensors
     * still read it, and the robot turned again.) */
    uint8_t i, best = HAL_IR_COUNT;
    int16_t v = (int16_t)self->p.speed_steps_s;
    for (i = 0; i < HAL_IR_COUNT; i++) {
        if (bearing[i] > -HALF_PI_MRAD && bearing[i] < HALF_PI_MRAD
            && (best == HAL_IR_COUNT || prox[i] > prox[best])) {
            best = i;
        }
    }
    if (self->turning == 0u && best < HAL_IR_COUNT && prox[best] > self->p.lost_turn_prox) {
        /* Negative bearings are on the right: turn left, and vice versa.
         * The paper gives no angle: 5..19 steps of a spin, about 55..210 deg
         * at 5 cm/s (a reconstruction). */
        self->turn_dir = bearing[best] < 0 ? (int8_t)1 : (int8_t)-1;
        self->turning = (uint8_t)(5u + rng_below(&self->rng, 15u));
    }
    if (self->turning > 0u) {
        self->turning--;
        hal_set_wheel_speeds(hal, (int16_t)(-self->turn_dir * v), (int16_t)(self->turn_dir * v));
    } else {
        hal_set_wheel_speeds(hal, v, v);
    }
}

void eaipp_step(eaipp_t *self, hal_t *hal)
{
    uint16_t prox[HAL_IR_COUNT];
    int16_t bearing[HAL_IR_COUNT];
    self->id = (uint8_t)(hal_robot_id(hal) & 0x7Fu);
    hear_all(self, hal);
    if (self->shun_steps > 0u) {
        self->shun_steps--;
    }
    switch (self->state) {
    case EAIPP_NEST:
    case EAIPP_FOOD:
        self->gradient = 0u;
        self->root = self->id;
        hal_set_wheel_speeds(hal, 0, 0);
        break;
    case EAIPP_LOST:
        read_prox(hal, prox, bearing);
        if (exit_due(self)) {
            self->state = EAIPP_EXITING;
            self->tx_cursor = 0u;
            lost_step(self, hal, prox, bearing);
        } else if (senses_network(self)) {
            self->state = EAIPP_EXPLORER;
        } else {
            lost_step(self, hal, prox, bearing);
        }
        break;
    case EAIPP_EXITING: {
        float vx, vy;
        int16_t l, r;
        const neighbour_t *nest = 0;
        uint8_t i;
        for (i = 0; i < self->nb.count; i++) {
            if (neighbour_is(&self->nb.n[i], EAIPP_ST_NEST)) {
                nest = &self->nb.n[i];
            }
        }
        if (nest != 0 && nest->age == 0u && nest->range_mm <= self->p.exit_near_mm) {
            /* Out of the waiting area, at the nest: search (EAIPP). */
            self->exited = 1u;
            self->exit_mm = 0xFFFFu;
            self->tx_cursor = 0u;
            self->state = EAIPP_EXPLORER;
            break;
        }
        if (!eaipp_exit_direction(self, &vx, &vy)) {
            self->state = EAIPP_LOST;
            self->tx_cursor = 0u;
            break;
        }
        read_prox(hal, prox, bearing);
        blend_obstacles(self, prox, bearing, &vx, &vy);
        self->heading_x = vx;
        self->heading_y = vy;
        eaipp_wheel_law(vx, vy, self->p.speed_steps_s, self->p.turn_hold_mrad, &self->turn_side, &l, &r);
        hal_set_wheel_speeds(hal, l, r);
        break;
    }
    case EAIPP_EXPLORER:
        if (!senses_network(self)) {
            self->state = EAIPP_LOST;
            self->retreating = 0u;
            break;
        }
        if (eaipp_extension_due(self)) {
            become_node(self, hal);
            break;
        }
        read_prox(hal, prox, bearing);
        {
            float vx, vy;
            int16_t l, r;
            eaipp_direction(self, prox, bearing, &vx, &vy);
            self->heading_x = vx;
            self->heading_y = vy;
            eaipp_wheel_law(vx, vy, self->p.speed_steps_s, self->p.turn_hold_mrad, &self->turn_side, &l, &r);
            hal_set_wheel_speeds(hal, l, r);
        }
        break;
    case EAIPP_NODE:
    default:
        hal_set_wheel_speeds(hal, 0, 0);
        if (!eaipp_gradient_update(self)) {
            /* Cut off from every source (section 4.3) for as long as a
             * neighbour takes to be forgotten: then lost. */
            if (++self->orphan_steps >= self->p.timeout_steps) {
                self->orphan_steps = 0u;
                leave(self, EAIPP_LOST);
            }
            break;
        }
        self->orphan_steps = 0u;
        eaipp_extinction_step(self);
        break;
    }
    hal_set_body_led(hal, (uint8_t)(self->state == EAIPP_NODE || self->state >= EAIPP_NEST));
    send_turn(self, hal);
}
