// Contact laws: how a grid node inside a collider moves relative to it (physics.md section 6).
//
// A law sees the nodes of one block that touch one collider and replaces their velocities
// relative to the collider. The engine calls it once per (block, collider), never per node, and
// each law's own loop is compiled inline (ContactLawOf), so a plain Coulomb node costs what a
// hard-coded Coulomb branch would. A law is one small type with `kName` and
// `apply(ContactNode&, const ContactStep&) const` (engine/contact_laws.h has the basic ones) and
// one row in the scene's law table (io/scene/contact_law_table.cpp).
#pragma once

#include "engine/types.h"

#include <memory>

namespace talus {

/// One grid node in contact with a collider, as a contact law sees it.
struct ContactNode {
  Vec3 v;    ///< velocity relative to the collider (m/s); the law replaces it
  Vec3 n;    ///< outward unit normal of the collider at the node
  Real mass; ///< node mass (kg)
};

/// What a law may need of the step besides the node.
struct ContactStep {
  Real dt = 0;
};

class ContactLaw {
public:
  virtual ~ContactLaw() = default;
  virtual const char* name() const = 0;
  /// Applies the law to `count` contact nodes of one block.
  virtual void apply(ContactNode* nodes, int count, const ContactStep& step) const = 0;
};

/// A law type as a ContactLaw: one virtual call per block, the per-node loop inlined.
template <class Law>
class ContactLawOf final : public ContactLaw {
public:
  explicit ContactLawOf(const Law& law) : law_(law) {}
  const char* name() const override { return Law::kName; }
  void apply(ContactNode* nodes, int count, const ContactStep& step) const override {
    for (int i = 0; i < count; ++i) law_.apply(nodes[i], step);
  }
  const Law& law() const { return law_; }

private:
  Law law_;
};

template <class Law>
std::shared_ptr<const ContactLaw> makeContactLaw(const Law& law) {
  return std::make_shared<ContactLawOf<Law>>(law);
}

} // namespace talus
