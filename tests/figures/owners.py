"""Who owns which experiment's figures (the lint names the owner of every figure it lists)."""

OWNERS = {
    "wransac": "P01",
    "epipolar": "P02",
    "track_init_ht": "P03",
    "track_init_hough": "P04",
    "akf_star": "P05",
    "ransac_crlb_pose": "P06",
    "capstone": "CAP",
}
