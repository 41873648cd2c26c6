#include "distributed/halo.hpp"

#include <array>

namespace rupture {

namespace {

/// The per-particle arrays a ghost takes from its owner, in message order.
template <class F>
void forEachGhostArray(ParticleStore& p, std::vector<double>& nodalMinimum, bool rotations, F&& f) {
  for (auto* v : {&p.x, &p.y, &p.z, &nodalMinimum}) f(*v);
  if (rotations)
    for (auto* v : {&p.qw, &p.qx, &p.qy, &p.qz}) f(*v);
}

}  // namespace

Halo::Halo(Communicator comm, std::vector<Neighbour> neighbours, bool rotations)
    : m_comm(comm), m_neighbours(std::move(neighbours)), m_rotations(rotations) {
  for (const Neighbour& n : m_neighbours) {
    m_sendBuffers.emplace_back(n.send.size() * static_cast<std::size_t>(valuesPerGhost()));
    m_receiveBuffers.emplace_back(n.receive.size() * static_cast<std::size_t>(valuesPerGhost()));
  }
}

std::size_t Halo::bytesSent() const {
  std::size_t bytes = 0;
  for (const auto& b : m_sendBuffers) bytes += b.size() * sizeof(double);
  return bytes;
}

void Halo::refresh(ParticleStore& particles, std::vector<double>& nodalMinimum) {
  if (m_neighbours.empty()) return;
  std::vector<Communicator::Message> sends, receives;
  for (std::size_t n = 0; n < m_neighbours.size(); ++n) {
    const Neighbour& nb = m_neighbours[n];
    double* out = m_sendBuffers[n].data();
    forEachGhostArray(particles, nodalMinimum, m_rotations, [&](const std::vector<double>& v) {
      for (std::int32_t k : nb.send) *out++ = v[k];
    });
    sends.push_back({nb.rank, m_sendBuffers[n].data(), m_sendBuffers[n].size()});
    receives.push_back({nb.rank, m_receiveBuffers[n].data(), m_receiveBuffers[n].size()});
  }
  m_comm.exchange(sends, receives);
  for (std::size_t n = 0; n < m_neighbours.size(); ++n) {
    const double* in = m_receiveBuffers[n].data();
    forEachGhostArray(particles, nodalMinimum, m_rotations, [&](std::vector<double>& v) {
      for (std::int32_t k : m_neighbours[n].receive) v[k] = *in++;
    });
  }
}

}  // namespace rupture
