/*
 * swarm-evolve nnea_evolve: the best genome (generation 61, fitness 1.08666666667),
 * the defaults of nnea's genome keys as C initialisers.  Generated: do not edit.
 */
#ifndef NNEA_EVOLVED_GENOME_H
#define NNEA_EVOLVED_GENOME_H

#define NNEA_EVOLVED_W_IN { 1110, -57, 1077, -625, -356, 2020, -1727, -204, -1190, -300, 1829, 23, -451, 406, -344, 114, 197, -1460, 970, -1758, -1277, -253, -1658, 150, -1420, 1824, -840, -354, 386, -1478, 1925, 260, 226, -770, -65, -2013, -41, 2032, 1164, 1105, 1667, -1012, 1711, -830, 1681, 2017, 275, -180, 1128, 2023, 1449, -68, 774, -971, 83, -432 }
#define NNEA_EVOLVED_W_REC { 1206, 1654, -1078, -1779, 2003, 1567, 1183, -594, -2023, -2037, 59, 1961, 1254, -1282, 247, 1998 }
#define NNEA_EVOLVED_B_HIDDEN { 530, -837, 2047, -2047 }
#define NNEA_EVOLVED_TAU { 247, 160, 134, 111 }
#define NNEA_EVOLVED_W_OUT { -1493, -1513, 1156, 977, 163, -1137, -13, -128, -1627, 31, -1469, 125 }
#define NNEA_EVOLVED_B_OUT { 595, 33, -1276 }

#endif
