//! `[[materials]]` and `[[sections]]`, and the element options that refer to them.

use super::*;

impl Builder<'_> {
    pub(super) fn materials(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "materials")? {
            t.check_keys(&["name", "E", "nu", "thickness", "alpha"])?;
            let name = id(
                self.doc,
                t.require("name", "the material's name")?,
                &t.child("name"),
            )?;
            let e = positive(&t, "E", "Young's modulus E")?;
            let nu = number(&t, "nu", "Poisson's ratio nu")?;
            if !(nu > -1.0 && nu < 0.5) {
                return Err(self.err(
                    t.get("nu").and_then(|n| n.pos),
                    &t.child("nu"),
                    InputErrorKind::Value,
                    format!("Poisson's ratio must lie in (-1, 0.5), got {nu}"),
                ));
            }
            let mut m = PlaneMaterial::new(e, nu);
            if t.get("thickness").is_some() {
                m = m.with_thickness(positive(&t, "thickness", "the thickness")?);
            }
            if let Some(a) = opt_number(&t, "alpha")? {
                m = m.with_alpha(a);
            }
            if self.materials.insert(name.name.clone(), m).is_some() {
                return Err(
                    self.invalid_at(&name, format!("duplicate material name `{}`", name.name))
                );
            }
        }
        Ok(())
    }

    pub(super) fn sections(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "sections")? {
            t.check_keys(&["name", "E", "A", "I", "depth", "alpha"])?;
            let name = id(
                self.doc,
                t.require("name", "the section's name")?,
                &t.child("name"),
            )?;
            let e = positive(&t, "E", "Young's modulus E")?;
            let a = positive(&t, "A", "the area A")?;
            let has_inertia = t.get("I").is_some();
            let i = if has_inertia {
                positive(&t, "I", "the second moment of area I")?
            } else {
                0.0
            };
            let mut s = FrameSection::new(e, a, i);
            if t.get("depth").is_some() {
                s = s.with_depth(positive(&t, "depth", "the section depth")?);
            }
            if let Some(al) = opt_number(&t, "alpha")? {
                s = s.with_alpha(al);
            }
            let prev = self.sections.insert(
                name.name.clone(),
                Section {
                    section: s,
                    has_inertia,
                },
            );
            if prev.is_some() {
                return Err(
                    self.invalid_at(&name, format!("duplicate section name `{}`", name.name))
                );
            }
        }
        Ok(())
    }

    pub(super) fn section(&self, t: &Table, frame: bool) -> Result<FrameSection, InputError> {
        let r = id(
            self.doc,
            t.require("section", "the name of a [[sections]] entry")?,
            &t.child("section"),
        )?;
        let Some(s) = self.sections.get(&r.name) else {
            return Err(self.unknown(&r, "section", self.sections.keys()));
        };
        if frame && !s.has_inertia {
            return Err(self.invalid_at(&r, format!(
                    "section `{}` has no moment of inertia I, which frame elements need (give I, or use bars)",
                    r.name
                ),
            ));
        }
        Ok(s.section)
    }

    pub(super) fn material(&self, t: &Table) -> Result<PlaneMaterial, InputError> {
        let r = id(
            self.doc,
            t.require("material", "the name of a [[materials]] entry")?,
            &t.child("material"),
        )?;
        self.materials
            .get(&r.name)
            .copied()
            .ok_or_else(|| self.unknown(&r, "material", self.materials.keys()))
    }

    pub(super) fn plane_options(
        &self,
        t: &Table,
    ) -> Result<(PlaneAnalysis, PlaneFormulation), InputError> {
        let analysis = match choice(
            t,
            "analysis",
            &["plane_strain", "plane_stress"],
            None,
            "plane analysis",
        )? {
            "plane_strain" => PlaneAnalysis::PlaneStrain,
            _ => PlaneAnalysis::PlaneStress,
        };
        let formulation = match choice(
            t,
            "formulation",
            &["QM6", "Q4"],
            Some("QM6"),
            "plane element formulation",
        )? {
            "Q4" => PlaneFormulation::Q4,
            _ => PlaneFormulation::QM6,
        };
        Ok((analysis, formulation))
    }

    pub(super) fn releases(&self, t: &Table) -> Result<Releases, InputError> {
        let mut r = Releases::default();
        if let Some(node) = t.get("releases") {
            let key = t.child("releases");
            let items: Vec<&crate::tree::Node> = match &node.value {
                Value::Array(items) => items.iter().collect(),
                _ => vec![node],
            };
            for (i, item) in items.into_iter().enumerate() {
                let k = format!("{key}[{}]", i + 1);
                match self.doc.string(item, &k)? {
                    "start" => r.start = true,
                    "end" => r.end = true,
                    other => {
                        return Err(self.err(
                            item.pos,
                            &k,
                            InputErrorKind::Value,
                            format!(
                                "unknown release \"{}\": use \"start\" and/or \"end\" (a hinge at that end)",
                                crate::tree::short(other)
                            ),
                        ))
                    }
                }
            }
        }
        Ok(r)
    }
}
