"""Digital image correlation of contact tests (thesis sec. 2.3.2): camera frames in,
displacement fields of the contact-stiffness branch out (``docs/dic.md``)."""
