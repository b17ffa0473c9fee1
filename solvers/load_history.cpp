#include "solvers/load_history.hpp"

#include "common/error.hpp"

#include <cmath>
#include <sstream>

namespace sartor {

LoadHistory::LoadHistory(std::vector<LoadKnot> knots, const std::string& what)
    : knots_(std::move(knots)) {
  if (knots_.empty()) throw InputError(what + ": no knot");
  for (std::size_t k = 0; k < knots_.size(); ++k) {
    const LoadKnot& knot = knots_[k];
    const std::string where = what + ": knot " + std::to_string(k + 1);
    if (!std::isfinite(knot.time) || !std::isfinite(knot.factor)) {
      throw InputError(where + " is not finite");
    }
    if (k == 0) continue;
    if (knot.time < knots_[k - 1].time) {
      throw InputError(where + " (t = " + std::to_string(knot.time) +
                       " s) comes before the knot ahead of it");
    }
    if (k >= 2 && knot.time == knots_[k - 2].time) {
      throw InputError(where + ": more than two knots at t = " + std::to_string(knot.time) + " s");
    }
  }
}

LoadHistory LoadHistory::parse(const std::string& text, const std::string& what) {
  std::vector<LoadKnot> knots;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ';')) {
    const std::size_t first = item.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    item = item.substr(first, item.find_last_not_of(" \t") + 1 - first);
    const std::size_t colon = item.find(':');
    LoadKnot knot;
    try {
      if (colon == std::string::npos) throw std::invalid_argument(item);
      std::size_t used_time = 0, used_factor = 0;
      const std::string time = item.substr(0, colon), factor = item.substr(colon + 1);
      knot.time = std::stod(time, &used_time);
      knot.factor = std::stod(factor, &used_factor);
      if (time.find_first_not_of(" \t", used_time) != std::string::npos ||
          factor.find_first_not_of(" \t", used_factor) != std::string::npos) {
        throw std::invalid_argument(item);
      }
    } catch (const std::exception&) {
      throw InputError(what + ": '" + item + "' is not TIME:FACTOR");
    }
    knots.push_back(knot);
  }
  return LoadHistory(std::move(knots), what);
}

double LoadHistory::before(double time) const {
  if (knots_.empty()) return 1.0;
  if (time <= knots_.front().time) return knots_.front().factor;
  for (std::size_t k = 1; k < knots_.size(); ++k) {
    const LoadKnot& a = knots_[k - 1];
    const LoadKnot& b = knots_[k];
    if (time <= b.time) {
      if (b.time == a.time) return a.factor;
      return a.factor + (time - a.time) / (b.time - a.time) * (b.factor - a.factor);
    }
  }
  return knots_.back().factor;
}

double LoadHistory::after(double time) const {
  if (knots_.empty()) return 1.0;
  if (time >= knots_.back().time) return knots_.back().factor;
  for (std::size_t k = knots_.size() - 1; k > 0; --k) {
    const LoadKnot& a = knots_[k - 1];
    const LoadKnot& b = knots_[k];
    if (time >= a.time) {
      if (b.time == a.time) return b.factor;
      return a.factor + (time - a.time) / (b.time - a.time) * (b.factor - a.factor);
    }
  }
  return knots_.front().factor;
}

std::vector<double> LoadHistory::times() const {
  std::vector<double> result;
  for (const LoadKnot& knot : knots_) {
    if (result.empty() || result.back() != knot.time) result.push_back(knot.time);
  }
  return result;
}

} // namespace sartor
