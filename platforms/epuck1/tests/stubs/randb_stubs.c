/* Stubs of platforms/epuck1/hal/epuck_lib_randb.h (see epuck_stubs.h). */
#include "epuck_lib_randb.h"
#include "epuck_stubs.h"

void e_init_randb(unsigned char mode) { (void)mode; }
void e_randb_set_range(unsigned char distance) { (void)distance; }
void e_randb_set_calculation(unsigned char value) { (void)value; }
void e_randb_store_light_conditions(void) {}

unsigned char e_randb_reception(finalDataRegister *data)
{
    int i;
    if (epuck_stub.randb_count <= 0) {
        return 0u;
    }
    data->data = epuck_stub.randb_data[0];
    data->bearing = epuck_stub.randb_bearing[0];
    data->range = epuck_stub.randb_range[0];
    data->max_peak = 0u;
    data->max_sensor = 0u;
    for (i = 1; i < epuck_stub.randb_count; i++) {
        epuck_stub.randb_data[i - 1] = epuck_stub.randb_data[i];
        epuck_stub.randb_bearing[i - 1] = epuck_stub.randb_bearing[i];
        epuck_stub.randb_range[i - 1] = epuck_stub.randb_range[i];
    }
    epuck_stub.randb_count--;
    return 1u;
}

void e_randb_send_all_data(unsigned int data)
{
    if (epuck_stub.randb_sends < STUB_QUEUE) {
        epuck_stub.randb_sent[epuck_stub.randb_sends] = data;
    }
    epuck_stub.randb_sends++;
}
