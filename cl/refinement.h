// clmesh — per-point state of Delaunay refinement (thesis §3.3.2: pStatus =
// input, oldSteiner, newSteiner, redundant; §3.4.1: midpoints), shared by
// off-center insertion and flip-flop deletion.
#ifndef CLMESH_REFINEMENT_H
#define CLMESH_REFINEMENT_H

#define CLM_POINT_INPUT 0
#define CLM_POINT_STEINER 1      // inserted in an earlier iteration
#define CLM_POINT_NEW 2          // off-center inserted in this iteration
#define CLM_POINT_NEW_MIDPOINT 3 // hull midpoint inserted in this iteration
#define CLM_POINT_REDUNDANT 4    // to be deleted by flip-flop
#define CLM_POINT_DELETED 5      // deleted: its slot is free
#define CLM_POINT_MIDPOINT 6     // hull midpoint inserted in an earlier iteration
#define CLM_POINT_ACUTE_HULL 7   // input point at a hull angle below the minimum angle
#define CLM_POINT_HULL 8         // any other input point on the hull

// Hull vertices stay on the hull: the boundary is fixed during refinement.
inline bool on_hull(int state) {
  return state == CLM_POINT_HULL || state == CLM_POINT_ACUTE_HULL || state == CLM_POINT_MIDPOINT ||
         state == CLM_POINT_NEW_MIDPOINT;
}

inline bool is_new_point(int state) {
  return state == CLM_POINT_NEW || state == CLM_POINT_NEW_MIDPOINT;
}

// Is c inside the diametral lens of the edge pa-pb? Triangle's encroachment
// test: c sees the edge at an angle whose cosine squared is at least `lens`
// (cos(2 x minimum angle) squared) while negative.
inline bool in_lens(double2 pa, double2 pb, double2 c, double lens) {
  const double2 da = pa - c, db = pb - c;
  const double dot = da.x * db.x + da.y * db.y;
  return dot < 0 && dot * dot >= lens * (da.x * da.x + da.y * da.y) * (db.x * db.x + db.y * db.y);
}

#endif
