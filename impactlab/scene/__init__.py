"""Domain objects: the ball, the face, the club head, the strike and the scene they make (re-exports)."""

from impactlab.scene.catalogue import club_preset
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.scene.core import Contact, Delivery, Impact, Scene
from impactlab.scene.materials import Ball, Face, Material, ball_preset, face_preset

__all__ = ["Ball", "ClubHead", "Contact", "Delivery", "Face", "Impact", "Material", "Scene", "Strike",
           "ball_preset", "club_preset", "face_preset"]
