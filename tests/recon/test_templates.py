"""recon.templates: which label pairs the articulated templates expect to touch."""

from recon.templates import expected_contact


def test_bed_headboard_mattress_is_a_designed_contact_and_leg_headboard_is_not():
    assert expected_contact("bed", "headboard", "mattress")
    assert expected_contact("bed", "mattress", "headboard")
    assert not expected_contact("bed", "leg", "headboard")
    assert not expected_contact("cabinet", "drawer", "drawer")
    assert expected_contact("bed", "frame", "leg")
