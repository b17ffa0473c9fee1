#pragma once

#include <algorithm>

namespace sartor::contact {

// How close a point now `distance` from a surface (a body, or a triangle of
// the cloth) may come within one step: a tenth of the contact offset, or
// half its distance where it is closer already. The penalty, which acts
// within the offset, then has the room to hold it.
inline double closest_allowed(double distance, double offset) {
  return std::min(0.5 * distance, 0.1 * offset);
}

// Conservative advancement: the largest t in [0, limit] at which
// distance(t), which is `start` at t = 0 and falls by at most `rate` per
// unit of t, has not yet reached `level` (limit where it never does). Each advance is the room
// left, (distance - level) / rate, so the advances shrink towards the
// first time the level is reached. Stopping only once they are below
// round-off, or after a fixed count, keeps t a continuous function of the
// state: a coarser stopping rule would make the step jump where a point
// needs one advance more, and the iterates of two machines would part at
// round-off.
template <class Distance>
double conservative_advance(const Distance& distance, double start, double level, double rate,
                            double limit) {
  if (!(rate > 0.0)) return limit;
  double t = 0.0, d = start;
  for (int k = 0; k < 50; ++k) {
    const double room = std::max(0.0, d - level) / rate;
    if (t + room >= limit) return limit;
    t += room;
    if (room <= 1e-14 * limit) break;
    d = distance(t);
  }
  return t;
}

} // namespace sartor::contact
