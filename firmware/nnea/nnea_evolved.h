/*
 * swarm-evolve nnea_evolve: the best genome (generation 103, fitness 0.4121250297666667),
 * the defaults of nnea's genome keys as C initialisers.  Generated: do not edit.
 */
#ifndef NNEA_EVOLVED_GENOME_H
#define NNEA_EVOLVED_GENOME_H

#define NNEA_EVOLVED_W_IN { -117, -402, -1592, -1034, -729, 168, -1640, 1727, 1274, -596, -110, 1053, 630, 985, 1646, -906, 1408, 1360, -1642, 2000, -837, 2008, 1837, 1661, 1944, -1163, 763, 1427, -2020, 1276, 876, 626, 1817, -1423, -383, 1341, 2046, -1194, -1196, -2046, -735, 687, -1425, -1544, 1249, 1588, -1071, -418, 1342, 1045, -2042, 1005, -451, 98, 2046, -2040 }
#define NNEA_EVOLVED_W_REC { 701, -1544, -398, 677, 1974, -1391, -1234, 2040, -1096, 2038, -1874, 1825, -1980, 1916, -487, -1875 }
#define NNEA_EVOLVED_B_HIDDEN { 2042, 1756, -1036, 722 }
#define NNEA_EVOLVED_TAU { 24, 216, 220, 246 }
#define NNEA_EVOLVED_W_OUT { -1322, -1523, -808, -354, -939, -1647, 1326, 1863, -1073, -1800, -851, -385 }
#define NNEA_EVOLVED_B_OUT { -1385, 55, -947 }

#endif
