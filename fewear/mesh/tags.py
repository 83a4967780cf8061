"""The facet tags the contact model reads from a mesh (plain integers, no DOLFINx).

Every body the contact solver takes (:mod:`fewear.contact.solver`) tags its contact surface with
``CONTACT_TAG`` (the bushing's bore, the flat's top) and its clamped surface, u = 0, with
``CLAMPED_TAG`` (the bushing's outer surface, the flat's bottom).
"""

CONTACT_TAG = 1
CLAMPED_TAG = 2
