// The far field's occlusion query for many rays at once (a batch's hits'
// rays that their near lists did not block): each ray walks as far_occluded
// walks it (far/occlude.inl), but up to `in_flight` rays take turns, a node
// each, and whatever a ray reads next (its next node, the leaves of the node
// it just met) is read ahead when it is chosen, and read a turn of the other
// rays later. A walk through a hierarchy bigger than the caches waits on
// each node it reads; in turns, the rays' waits overlap. Included by
// light/kernels_impl.cpp inside its width's namespace.

RAYCAST_INLINE void read_node_ahead(const bvh_view& v, uint32_t ref) {
  const char* n = reinterpret_cast<const char*>(v.nodes + ref);
  for (int line = 0; line < int(sizeof(bvh_node)); line += 64) __builtin_prefetch(n + line);
}
RAYCAST_INLINE void read_leaf_ahead(const bvh_view& v, uint32_t ref) {
  const float* b = v.leaf + size_t(bvh_ref::first(ref)) * 4;
  __builtin_prefetch(b), __builtin_prefetch(b + 4 * bvh_ref::count(ref) - 1);
}

// One ray's walk: its query, the inner node it visits next (empty: none),
// the leaves its last node met (tested on its next turn), and its stack.
struct group_walk {
  const far_query* q = nullptr;
  far_ray ray;
  uint32_t next = bvh_ref::empty;
  int leaves = 0, sp = 0;
  uint32_t leaf[8];
  uint32_t stack[192];
};

// A turn of walk w: its last node's leaves, then its next node, whose leaves
// and next node it reads ahead. Whether the ray is blocked; done: whether
// its walk has ended.
RAYCAST_INLINE bool group_turn(const bvh_view& v, group_walk& w, bool& done) {
  const far_query& q = *w.q;
  for (int i = 0; i < w.leaves; ++i)
    if (leaf_blocks(v, w.leaf[i], w.ray, q.t0, q.tmax, q.skip)) return true;
  w.leaves = 0;
  if (w.next == bvh_ref::empty) {
    done = w.sp == 0;
    if (!done) read_node_ahead(v, w.next = w.stack[--w.sp]);
    return false;
  }
  const bvh_node& n = v.nodes[w.next];
  const uint32_t sign = w.ray.sign;
  uint32_t inner = 0;
  for (uint32_t b = visit_order.of[sign][w.ray.meets(n, q.t0, q.tmax)]; b != 0; b &= b - 1) {
    const uint32_t o = uint32_t(__builtin_ctz(b)), child = n.child[o ^ sign];
    if (!bvh_ref::is_leaf(child)) {
      inner |= 1u << o;
    } else {
      w.leaf[w.leaves++] = child;
      read_leaf_ahead(v, child);
    }
  }
  w.next = bvh_ref::empty;
  if (inner != 0) {
    w.next = n.child[__builtin_ctz(inner) ^ sign];
    for (inner &= inner - 1; inner != 0;) {
      const uint32_t o = 31u - uint32_t(__builtin_clz(inner));
      w.stack[w.sp++] = n.child[o ^ sign];
      inner ^= 1u << o;
    }
  } else if (w.sp > 0) {
    w.next = w.stack[--w.sp];
  }
  if (w.next != bvh_ref::empty) read_node_ahead(v, w.next);
  done = false;
  return false;
}

// blocked[i] = far_occluded's verdict for query q[i], i < n: up to in_flight
// rays walk in turns, each slot taking the next query as its ray ends. A ray
// first walks a few nodes alone: most rays that leave the spheres (from a
// packed box's face) end within them, and walk on no turns.
void far_occluded_many(const bvh_view& v, const far_query* q, uint32_t n, uint8_t* blocked) {
  constexpr int in_flight = 32, alone = 4;
  if (v.root == bvh_ref::empty || bvh_ref::is_leaf(v.root)) {
    for (uint32_t i = 0; i < n; ++i) blocked[i] = far_occluded(v, q[i].o, q[i].d, q[i].t0, q[i].tmax, q[i].skip);
    return;
  }
  group_walk walk[in_flight];
  uint32_t started = 0, live = 0;
  const auto start = [&](int s) {
    for (; started < n; ++started) {
      blocked[started] = 0;
      if (!(q[started].t0 <= q[started].tmax)) continue;
      group_walk& w = walk[s];
      w.q = &q[started];
      w.ray = far_ray(w.q->o, w.q->d);
      w.next = v.root, w.leaves = 0, w.sp = 0;
      bool done = false, hit = false;
      for (int t = 0; t < alone && !hit && !done; ++t) hit = group_turn(v, w, done);
      if (hit || done) {
        blocked[started] = hit;
        continue;
      }
      ++started;
      live |= 1u << s;
      return;
    }
  };
  for (int s = 0; s < in_flight; ++s) start(s);
  while (live != 0)
    for (uint32_t b = live; b != 0; b &= b - 1) {
      const int s = __builtin_ctz(b);
      bool done = false;
      const bool hit = group_turn(v, walk[s], done);
      if (!hit && !done) continue;
      blocked[walk[s].q - q] = hit;
      live &= ~(1u << s);
      start(s);
    }
}
