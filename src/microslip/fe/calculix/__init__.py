"""CalculiX (``ccx``) on the clamped bar: deck, run and read-back.

- :mod:`~microslip.fe.calculix.mesh`: the box's mesh levels (:class:`MeshSpec`);
- :mod:`~microslip.fe.calculix.case`: the box's validated load case (:class:`FECase`);
- :mod:`~microslip.fe.calculix.deck`: the ``.inp`` cards, one tested function per keyword card;
- :mod:`~microslip.fe.calculix.runner`: ``ccx`` with a time-out and typed failures;
- :mod:`~microslip.fe.calculix.readers`: ``.dat``, ``.sta`` and ``.frd`` readers;
- :mod:`~microslip.fe.calculix.collect`: the contact status rule and the box's
  :class:`CalculixDetails`;
- :mod:`~microslip.fe.calculix.boxrun`: the box of an :class:`FECase` on the mesh deck
  (20-node ``box_hexmesh``, the symmetry plane a support), read into an
  :class:`~microslip.fe.result.FELoopResult` (``run_case``, ``read_results``);
- :mod:`~microslip.fe.calculix.meshdeck`: the deck of the user's own
  :class:`~microslip.fe.hexmesh.HexMesh` with named sets and
  :class:`~microslip.fe.meshload.MeshLoad` loads (issue 22), and
  :mod:`~microslip.fe.calculix.meshhistory` its load history;
- :mod:`~microslip.fe.calculix.meshrun`: that deck run and read into a
  :class:`~microslip.fe.calculix.meshrun.MeshCalculixResult`;
- :mod:`~microslip.fe.calculix.contactform`: the deck's contact formulations (face-to-face,
  node-to-surface);
- :mod:`~microslip.fe.calculix.compare`: the built-in solver against CalculiX on the same
  mesh, like with like (``validate --mesh``, issue 29).
"""
