# SPDX-License-Identifier: GPL-3.0-or-later
"""Where the add-on's panels live: the 3D view's sidebar, tab "Polycube"."""


class SidebarTab:
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = "Polycube"
