/* clmesh — a constant of GPU-QM-V's election (offcenter_insertion.cl), shared by the device and
 * the host. Plain C, valid in OpenCL C and C++. */
#ifndef CLMESH_ELECTION_H
#define CLMESH_ELECTION_H

/* A second round of the election runs when the first elects fewer than one bad triangle in
 * CLM_SECOND_ROUND_SHARE (see settle_elected). */
#define CLM_SECOND_ROUND_SHARE 3

#endif
