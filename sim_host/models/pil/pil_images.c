/* pil_images.c - pil_images.h: the generated table. */
#include "pil_images.h"

#include <string.h>

#include "pil_image_list.h"

static const pil_image_t images[] = { PIL_IMAGE_LIST };

const pil_image_t *pil_image_at(size_t i)
{
    return i < sizeof images / sizeof images[0] ? &images[i] : NULL;
}

const pil_image_t *pil_image_find(const char *name)
{
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++) {
        if (strcmp(images[i].name, name) == 0) {
            return &images[i];
        }
    }
    return NULL;
}
