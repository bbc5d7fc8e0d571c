#include "swarmsim/drawing.h"

int drawing_add(drawing_t *d, const draw_shape_t *shape)
{
    if (d->count >= d->cap) {
        return -1;
    }
    d->shapes[d->count++] = *shape;
    return 0;
}
